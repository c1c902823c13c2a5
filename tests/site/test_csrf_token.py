"""The kit's CSRF token (apps.kit.csrf): Django's shape and side effects, one read of the OS's
random source per token, and a form posted with it passes Django's own check."""

from __future__ import annotations

import os
from collections import Counter

import pytest
from django.http import HttpResponse
from django.middleware.csrf import (
    CSRF_ALLOWED_CHARS,
    CSRF_TOKEN_LENGTH,
    CsrfViewMiddleware,
    _unmask_cipher_token,
)
from django.test import RequestFactory

from apps.kit import csrf
from apps.kit.csrf import csrf_token, random_chars


def check(request) -> HttpResponse | None:
    """What CsrfViewMiddleware answers for `request` (None: let through)."""
    middleware = CsrfViewMiddleware(lambda r: HttpResponse())
    middleware.process_request(request)
    return middleware.process_view(request, lambda r: HttpResponse(), (), {})


def test_a_token_unmasks_to_the_requests_secret_and_a_new_visitor_gets_one():
    request = RequestFactory().get("/")
    token = csrf_token(request)
    assert len(token) == CSRF_TOKEN_LENGTH and set(token) <= set(CSRF_ALLOWED_CHARS)
    secret = request.META["CSRF_COOKIE"]
    assert _unmask_cipher_token(token) == secret
    assert request.META["CSRF_COOKIE_NEEDS_UPDATE"] is True  # the cookie goes out with it
    again = csrf_token(request)
    assert again != token and _unmask_cipher_token(again) == secret  # masked afresh


def test_a_form_posted_with_the_token_passes_djangos_check_and_a_forged_one_does_not():
    page = RequestFactory().get("/")
    token = csrf_token(page)
    cookie = page.META["CSRF_COOKIE"]
    factory = RequestFactory(enforce_csrf_checks=True)
    posted = factory.post("/", {"csrfmiddlewaretoken": token}, HTTP_COOKIE=f"csrftoken={cookie}")
    assert check(posted) is None
    forged = factory.post(
        "/", {"csrfmiddlewaretoken": random_chars(64)}, HTTP_COOKIE=f"csrftoken={cookie}"
    )
    assert check(forged).status_code == 403


def test_a_token_reads_the_random_source_once(monkeypatch):
    """Django reads it once per character, letting go of the GIL each time (the cost this
    module exists to avoid)."""
    reads = []
    real = os.urandom
    monkeypatch.setattr(csrf.os, "urandom", lambda n: reads.append(n) or real(n))
    csrf_token(RequestFactory().get("/"))  # a new visitor: the secret and the mask
    assert len(reads) == 2


@pytest.mark.parametrize("count", [1, 32, 200])
def test_random_chars_are_of_the_alphabet_and_spread_evenly(count):
    drawn = random_chars(count)
    assert len(drawn) == count and set(drawn) <= set(CSRF_ALLOWED_CHARS)
    if count == 200:
        # 4,000 of each expected (σ ≈ 63): a plain `byte % 62` would draw the first eight a
        # quarter more often than the rest.
        tally = Counter(random_chars(62 * 4000))
        assert set(tally) == set(CSRF_ALLOWED_CHARS)
        assert max(tally.values()) < 1.15 * min(tally.values())
