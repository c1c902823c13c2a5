"""A kept screen (apps.kit.screen_cache) is never a second source of truth: it is served
only while the state, the clock's displayed values and the request are those it was rendered
for, each response carries its own request's CSRF token, and one-shot messages are never kept."""

from __future__ import annotations

import re

import pytest
from django.test import Client

from apps.kit import screen_cache
from events import lifecycle
from events.commands import perform_action
from tests.micromail.cast import LATE_AT

pytestmark = pytest.mark.django_db

_TOKEN = re.compile(r'name="csrfmiddlewaretoken" value="([^"]+)"')
_HEADER_TOKEN = re.compile(r'"X-CSRFToken": "([^"]*)"')


@pytest.fixture(autouse=True)
def no_kept_screens():
    screen_cache.clear()
    yield
    screen_cache.clear()


def load(client: Client, url: str, **headers) -> str:
    response = client.get(url, headers=headers)
    assert response.status_code == 200
    return response.content.decode()


def without_tokens(html: str) -> str:
    return _HEADER_TOKEN.sub("", _TOKEN.sub("", html))


def test_an_unchanged_page_is_served_again_with_a_token_of_its_own(mail_url):
    client = Client()
    first = load(client, mail_url("?folder=inbox"))
    second = load(client, mail_url("?folder=inbox"))

    assert screen_cache.cache_info() == (1, 1)
    assert without_tokens(first) == without_tokens(second)
    assert screen_cache.CSRF_PLACEHOLDER not in first + second
    assert _TOKEN.findall(first) != _TOKEN.findall(second)  # masked afresh per response


def test_a_kept_pages_form_works_for_another_browser(mail_url):
    load(Client(), mail_url("?folder=inbox"))  # rendered for the first browser
    other = Client(enforce_csrf_checks=True)
    html = load(other, mail_url("?folder=inbox"))
    assert screen_cache.cache_info()[0] == 1
    token = _TOKEN.search(html).group(1)

    response = other.post(
        mail_url("emails/budget-review/flag"), {"csrfmiddlewaretoken": token}, follow=True
    )

    assert response.status_code == 200
    assert "Unflag “Q3 budget review”" in response.content.decode()


def test_an_action_shows_at_once(mail_run, mail_url):
    client = Client()
    assert "Unflag “Q3 budget review”" not in load(client, mail_url("?folder=inbox"))
    perform_action(mail_run, "flag", {"email_id": "budget-review"})
    assert "Unflag “Q3 budget review”" in load(client, mail_url("?folder=inbox"))


def test_a_scenario_event_shows_at_once(mail_run, mail_url):
    client = Client()
    assert "late-report" not in load(client, mail_url("?folder=inbox"))
    lifecycle.advance(mail_run, LATE_AT)
    assert "late-report" in load(client, mail_url("?folder=inbox"))


def test_the_clock_moving_past_what_the_page_shows_renders_it_again(mail_run, mail_url):
    client = Client()
    lifecycle.advance(mail_run, LATE_AT)  # "late-report" arrives: "Just now"
    before = load(client, mail_url("?folder=inbox"))
    lifecycle.advance(mail_run, LATE_AT + 600)  # nothing fires; its "time ago" moves on
    after = load(client, mail_url("?folder=inbox"))

    assert screen_cache.cache_info() == (0, 2)
    assert without_tokens(before) != without_tokens(after)


def test_a_fragment_and_the_whole_page_are_kept_apart(mail_url):
    client = Client()
    whole = load(client, mail_url("?folder=inbox"))
    fragment = load(client, mail_url("?folder=inbox"), HX_Request="true")
    assert "<html" in whole and "<html" not in fragment
    assert "<html" not in load(client, mail_url("?folder=inbox"), HX_Request="true")
    assert screen_cache.cache_info() == (1, 2)


def test_a_toast_is_shown_once_and_never_kept(mail_url):
    client = Client()
    load(client, mail_url("?folder=inbox"))
    shown = client.post(mail_url("emails/budget-review/flag"), follow=True).content.decode()
    again = load(client, mail_url("?folder=inbox"))

    assert 'class="toast"' in shown
    assert 'class="toast"' not in again


def test_off_every_load_is_rendered(mail_url, settings):
    settings.SENTINEL_SCREEN_CACHE = False
    client = Client()
    load(client, mail_url("?folder=inbox"))
    html = load(client, mail_url("?folder=inbox"))
    assert screen_cache.cache_info() == (0, 0)
    assert screen_cache.CSRF_PLACEHOLDER not in html


def test_closing_the_run_forgets_its_screens(
    mail_run, mail_url, django_capture_on_commit_callbacks
):
    load(Client(), mail_url("?folder=inbox"))
    with django_capture_on_commit_callbacks(execute=True):
        lifecycle.close(mail_run)
    assert not [key for key in screen_cache._screens if key[0] == mail_run.pk]
    assert screen_cache._held[0] == 0


def test_kept_screens_are_bounded_by_their_size(mail_url, monkeypatch):
    inbox = load(Client(), mail_url("?folder=inbox"))
    monkeypatch.setattr(screen_cache, "MAX_SCREEN_BYTES", len(inbox) + 1)
    load(Client(), mail_url("?folder=sent"))  # the older screen goes to make room
    assert [key[1] for key in screen_cache._screens] == [mail_url("?folder=sent")]
    assert screen_cache._held[0] == len(
        screen_cache._screens[next(iter(screen_cache._screens))].html
    )
