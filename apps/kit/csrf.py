"""A page's CSRF token, as Django's `get_token` makes it, with its random characters drawn in one
read of the OS's random source instead of one read per character.

Django draws each character with `secrets.choice`, and each read of the random source lets go of
the GIL. With both request threads busy (a hundred agents loading pages), the thread that let
go waited up to a whole switch interval to get it back, each time: a token took up to ~100 ms,
and drawing tokens was 12 % of the server's samples under `bench_scale`. One read lets go once.

The token has Django's shape — 32 characters of mask, then the secret enciphered with it — and
the secret lives where Django keeps it (`request.META["CSRF_COOKIE"]`, sent back as the cookie),
so `CsrfViewMiddleware` checks a posted form exactly as it checks its own tokens.
"""

from __future__ import annotations

import os

from django.http import HttpRequest
from django.middleware.csrf import CSRF_ALLOWED_CHARS, CSRF_SECRET_LENGTH

_CHARS = CSRF_ALLOWED_CHARS
# The largest multiple of the alphabet's size that fits a byte: bytes at or above it are
# dropped, so every character stays equally likely (a plain `% 62` would favour the first 8).
_FAIR_BELOW = 256 - 256 % len(_CHARS)


def random_chars(count: int) -> str:
    """`count` characters of the CSRF alphabet, uniform and unpredictable."""
    picked: list[str] = []
    while len(picked) < count:
        # Twice what is needed: a byte is dropped 1 time in 32, so one read almost always does.
        picked += [_CHARS[b % len(_CHARS)] for b in os.urandom(2 * count) if b < _FAIR_BELOW]
    return "".join(picked[:count])


def csrf_token(request: HttpRequest) -> str:
    """What `django.middleware.csrf.get_token(request)` returns, with the same side effects: the
    request's secret (a new one for a new visitor), marked to be sent back as the cookie, masked
    afresh for this response."""
    secret = request.META.get("CSRF_COOKIE")
    if secret is None:
        secret = random_chars(CSRF_SECRET_LENGTH)
        request.META["CSRF_COOKIE"] = secret
    request.META["CSRF_COOKIE_NEEDS_UPDATE"] = True  # renew the cookie's expiry, as Django does
    mask = random_chars(CSRF_SECRET_LENGTH)
    cipher = "".join(
        _CHARS[(_CHARS.index(s) + _CHARS.index(m)) % len(_CHARS)]
        for s, m in zip(secret, mask, strict=True)
    )
    return mask + cipher
