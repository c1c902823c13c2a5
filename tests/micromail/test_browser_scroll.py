"""The message list keeps its place: open the 150th message of a full inbox in Chromium, and the
list is still where it was; a message delivered while reading does not move it either.

Opening a message is a new page (its own URL, hx-boost swaps the body), so without
static/micromail/micromail.js the list would be back at the top; live pushes are kept by static/site/live.js.
"""

from __future__ import annotations

import json
import re

import pytest
from django.conf import settings
from playwright.sync_api import Page, expect

from tests.browser_story import BrowserStory

# tests/micromail/conftest.py binds `browser` to a django.test.Client; this module needs the
# Chromium one from tests/conftest.py.
from tests.conftest import browser  # noqa: F401
from tests.micromail.cast import inbox_scenario

pytestmark = pytest.mark.browser

WAIT_MS = 15000  # a 150-message page on a busy machine: generous, never a speed assertion

LATE_MAIL = "base-40"  # "Partner sync recap": held back, delivered while the 150th message is open
LATE_AT = 30.0


def full_inbox_scenario() -> dict:
    """Every catalog message preloaded (as dev.json) except one, which arrives at LATE_AT."""
    catalog = settings.BASE_DIR / "fixtures" / "micromail" / "emails.jsonl"
    ids = [json.loads(line)["id"] for line in catalog.read_text().splitlines() if line.strip()]
    return inbox_scenario(
        "browser-micromail-full-inbox",
        "Read the oldest mail.",
        [i for i in ids if i != LATE_MAIL],
        {"time": LATE_AT, "type": "new_email", "payload": {"email_id": LATE_MAIL}},
    )


def message_list(page: Page):
    return page.locator("#message-list")


def scroll_top(page: Page) -> float:
    return message_list(page).evaluate("list => list.scrollTop")


def rows(page: Page):
    return page.get_by_role("list", name="Messages").get_by_role("link")


def test_opening_the_150th_message_keeps_the_list_where_it_was(live_site, browser):  # noqa: F811
    """Also: a live push keeps it, closing the message keeps it, and rows name their parts."""
    story = BrowserStory.start(live_site, browser, full_inbox_scenario())
    page = story.page
    expect(page.get_by_role("heading", level=1, name="Inbox")).to_be_visible(timeout=WAIT_MS)
    assert rows(page).count() >= 150
    # Each row's accessible name says its parts apart: state, sender, subject, time, marks.
    expect(rows(page).first).to_have_accessible_name(
        re.compile(r"^(Unread\. )?From [^.]+\. Subject: .+\. (\d+ min ago|Just now|\d\d:\d\d)\.")
    )

    # Scroll the list down to the 150th message, as a person would with the wheel.
    target = rows(page).nth(149)
    target.scroll_into_view_if_needed()
    before = scroll_top(page)
    assert before > 5000, "the 150th row is far down a list that scrolls on its own"
    name = target.get_attribute("aria-label")
    subject = re.search(r"Subject: (.*?)\. ", name).group(1)

    target.click()
    expect(page.get_by_role("heading", level=2, name=subject)).to_be_visible(timeout=WAIT_MS)
    expect(page).to_have_url(re.compile(r"[?&]email="))
    opened = page.locator("li.message.opened a.row-link")
    expect(opened).to_have_attribute("aria-current", "true")
    assert scroll_top(page) == pytest.approx(before, abs=1)
    expect(opened).to_be_in_viewport()

    # A message delivered meanwhile is pushed into the list; the list stays put.
    count = rows(page).count()
    story.advance(LATE_AT)
    expect(rows(page)).to_have_count(count + 1, timeout=WAIT_MS)
    assert scroll_top(page) == pytest.approx(before, abs=1)
    expect(page.get_by_role("heading", level=2, name=subject)).to_be_visible()

    # Back to the list without the message (the reading pane's Close): still the same place.
    page.get_by_role("link", name="Close message").click()
    expect(page).not_to_have_url(re.compile(r"[?&]email="), timeout=WAIT_MS)
    expect(page.locator("li.message.opened")).to_have_count(0)
    assert scroll_top(page) == pytest.approx(before, abs=1)
