"""The message-list row cache (apps.kit.fragments, used by the kit's `{% rows %}`) is never a second source
of truth: a page built from cached rows is the page a fresh render gives, a state change shows
at once, and the "time ago" text follows the run's clock while the rest of the row is reused."""

from __future__ import annotations

import re

import pytest

from apps.kit import fragments, screen_cache
from apps.kit.live import without_csrf_tokens
from events import lifecycle
from events.commands import perform_action
from tests.micromail.cast import LATE_AT
from tests.micromail.test_pages import text

pytestmark = pytest.mark.django_db

_HTMX_CSRF_HEADER = re.compile(r'("X-CSRFToken": ")[^"]*(")')
_ROW = re.compile(r'<li class="message[ "].*?</li>', re.DOTALL)
_ROW_ID = re.compile(r'id="select-([^"]+)"')


def page(browser, url: str) -> str:
    """The page as a browser gets it, with the per-request CSRF token values blanked (Django
    masks them afresh on every response; nothing else on the page varies between requests).
    Rendered afresh each time (no kept screen), so the rows come through the row cache."""
    screen_cache.clear()
    html = without_csrf_tokens(text(browser.get(url)))
    return _HTMX_CSRF_HEADER.sub(r"\1\2", html)


def rows(html: str) -> dict[str, str]:
    """The message-list rows of a page, by email id."""
    return {_ROW_ID.search(row).group(1): row for row in _ROW.findall(html)}


SCREENS = [
    "?folder=inbox",
    "?folder=inbox&filter=unread",
    "?folder=inbox&email=team-lunch",  # a row marked as the open one
    "?folder=inbox&q=report&scope=all",  # rows name their folder
    "?folder=archive",
]


def test_a_page_of_cached_rows_is_byte_identical_to_a_fresh_render(mail_run, mail_url, browser):
    # Warm the cache through a history of states and clock readings, so that a key missing an
    # input would hand out a row rendered for an earlier state or time.
    for screen in SCREENS:
        page(browser, mail_url(screen))
    perform_action(mail_run, "flag", {"email_id": "budget-review"})
    lifecycle.advance(mail_run, LATE_AT + 30)
    for screen in SCREENS:
        page(browser, mail_url(screen))
    perform_action(mail_run, "pin", {"email_id": "late-report"})
    perform_action(mail_run, "move", {"email_id": "vendor-quote", "folder": "archive"})
    lifecycle.advance(mail_run, LATE_AT + 400)
    for screen in SCREENS:
        page(browser, mail_url(screen))

    hits, misses = fragments.cache_info()
    warm = [page(browser, mail_url(screen)) for screen in SCREENS]
    assert fragments.cache_info()[1] == misses and fragments.cache_info()[0] > hits  # all cached
    fragments.clear()  # also restarts the counts
    fresh = [page(browser, mail_url(screen)) for screen in SCREENS]
    assert fragments.cache_info()[1] > 0
    assert warm == fresh


@pytest.mark.parametrize(
    ("email_id", "action", "before", "after"),
    [
        (
            "budget-review",
            "flag",
            'aria-label="Flag “Q3 budget review”"',
            'aria-label="Unflag “Q3 budget review”" aria-pressed="true"',
        ),
        (
            "vendor-quote",
            "pin",
            'aria-label="Pin “Quote for the new laptops”"',
            'aria-label="Unpin “Quote for the new laptops”" aria-pressed="true"',
        ),
        ("budget-review", "mark_read", '<li class="message unread">', '<li class="message">'),
        ("team-lunch", "mark_unread", '<li class="message">', '<li class="message unread">'),
    ],
)
def test_a_state_change_shows_on_the_next_render_of_the_row(
    mail_run, mail_url, browser, email_id, action, before, after
):
    assert before in rows(page(browser, mail_url()))[email_id]
    page(browser, mail_url())  # the row is now served from the cache
    perform_action(mail_run, action, {"email_id": email_id})
    row = rows(page(browser, mail_url()))[email_id]
    assert after in row and before not in row


def test_opening_a_message_shows_its_row_read_and_open(mail_run, mail_url, browser):
    assert 'class="message unread"' in rows(page(browser, mail_url()))["budget-review"]
    row = rows(page(browser, mail_url("?folder=inbox&email=budget-review")))["budget-review"]
    assert row.startswith('<li class="message opened">') and 'aria-current="true"' in row


def test_time_ago_advances_with_the_run_clock(mail_run, mail_url, browser):
    # Preloaded mail arrived five minutes before t=0; late-report arrives at LATE_AT.
    assert ">5 min ago</time>" in rows(page(browser, mail_url()))["budget-review"]
    lifecycle.advance(mail_run, LATE_AT + 5)
    shown = rows(page(browser, mail_url()))
    assert ">just now</time>" in shown["late-report"]
    assert ">7 min ago</time>" in shown["budget-review"]
    lifecycle.advance(mail_run, LATE_AT + 200)
    assert ">3 min ago</time>" in rows(page(browser, mail_url()))["late-report"]
    lifecycle.advance(mail_run, 600)
    assert ">15 min ago</time>" in rows(page(browser, mail_url()))["budget-review"]


def test_a_clock_that_moves_within_the_same_minute_reuses_every_row(mail_run, mail_url, browser):
    shown = page(browser, mail_url())
    lifecycle.advance(mail_run, 30)  # every row still reads "5 min ago"
    hits, misses = fragments.cache_info()
    later = page(browser, mail_url())
    assert fragments.cache_info() == (hits + len(rows(shown)), misses)
    assert rows(later) == rows(shown)


def test_only_the_time_text_differs_when_the_clock_crosses_a_minute(mail_run, mail_url, browser):
    shown = rows(page(browser, mail_url()))
    lifecycle.advance(mail_run, 60)
    later = rows(page(browser, mail_url()))
    assert later.keys() == shown.keys()
    for email_id, row in shown.items():
        # The time shows twice: the visible text and its sentence in the row's accessible name.
        assert ">5 min ago</time>" in row and ". 5 min ago." in row
        assert later[email_id] == row.replace(">5 min ago</time>", ">6 min ago</time>").replace(
            ". 5 min ago.", ". 6 min ago."
        )
