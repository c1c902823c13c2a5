"""MicroMail's command bar in a real browser, as Outlook's: icon-and-label commands over the
checked messages and the open one, "Move to" and "More actions" as menus (finding: the list's
actions were unstyled default buttons and a native select, as in a debug form)."""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import expect

from tests.browser_story import BrowserStory
from tests.conftest import browser  # noqa: F401  (the Chromium fixture)
from tests.micromail.test_browser import inbox_link

pytestmark = pytest.mark.browser

FIRST, SECOND, KEPT = "base-01", "base-02", "base-30"
LATE, LATE_AT = "base-40", 30.0  # arrives while a menu is open


def scenario() -> dict:
    return {
        "id": "browser-micromail-command-bar",
        "environment": "micromail",
        "prompt": "Tidy the inbox.",
        "start_page": "HOST_ADDRESS/micromail",
        "condition_at": 300.0,
        "event_timeline_end": 600.0,
        "kill_at": 600.0,
        "taxonomy": {},
        "events": [
            {
                "time": 0.0,
                "type": "preload_emails",
                "payload": {"email_ids": [FIRST, SECOND, KEPT]},
            },
            {"time": LATE_AT, "type": "new_email", "payload": {"email_id": LATE}},
        ],
        "eval_sql": "SELECT 1",
    }


def test_checked_messages_move_through_the_menu_and_the_open_one_is_flagged(live_site, browser):  # noqa: F811
    story = BrowserStory.start(live_site, browser, scenario())
    page = story.page
    bar = page.get_by_role("toolbar", name="Actions on selected messages")
    for label in ("Delete", "Archive", "Mark as read", "Mark as unread", "Flag"):
        expect(bar.get_by_role("button", name=label, exact=True)).to_be_visible()
    menu = bar.get_by_role("list", name="Move selected messages to")
    expect(menu).to_be_hidden()  # a menu until opened, not a row of buttons

    messages = page.get_by_role("list", name="Messages").get_by_role("listitem")
    expect(messages).to_have_count(3)
    for n in (0, 1):
        messages.nth(n).get_by_role("checkbox").check()
    bar.get_by_text("Move to", exact=True).click()
    expect(menu).to_be_visible()
    menu.get_by_role("button", name="Junk Email").click()
    expect(page.get_by_text("2 emails moved to Junk Email")).to_be_visible()
    expect(messages).to_have_count(1)

    # The open message's own bar: Flag, then the same place offers Unflag.
    messages.first.get_by_role("link").click()
    pane = page.get_by_role("toolbar", name="Message actions")
    pane.get_by_role("button", name="Flag", exact=True).click()
    expect(pane.get_by_role("button", name="Unflag", exact=True)).to_be_visible()
    pane.get_by_text("Move to", exact=True).click()
    pane.get_by_role("list", name="Move to folder").get_by_role("button", name="Archive").click()
    expect(page.get_by_role("list", name="Messages").get_by_role("listitem")).to_have_text(
        re.compile("Nothing in Inbox")
    )
    expect(inbox_link(page)).to_be_visible()
    assert [name for name, _ in story.actions()] == ["move", "move", "flag", "move"]


def test_a_message_pushed_while_a_menu_is_open_leaves_it_open(live_site, browser):  # noqa: F811
    """A live push re-renders the list, menus and all: the one the person opened stays open (it
    closed under them, and a click on one of its items then found nothing to click)."""
    story = BrowserStory.start(live_site, browser, scenario())
    page = story.page
    bar = page.get_by_role("toolbar", name="Actions on selected messages")
    messages = page.locator("#message-list li.message")
    expect(messages).to_have_count(3)
    bar.get_by_text("Move to", exact=True).click()
    menu = bar.get_by_role("list", name="Move selected messages to")
    expect(menu).to_be_visible()

    story.advance(LATE_AT)
    expect(messages).to_have_count(4)  # the list was pushed
    expect(menu).to_be_visible()
    expect(bar.get_by_role("list", name="More actions")).to_be_hidden()  # closed stays closed


def test_a_menu_opened_while_a_command_is_answered_stays_open(live_site, browser):  # noqa: F811
    """A command's own answer redraws the page after its push has already shown the change: a
    menu the person opened in between stays open (on a loaded machine it closed under them, and
    the click on one of its items found nothing to click). The answer is held back here until
    the menu is open, which a loaded machine does by chance."""
    story = BrowserStory.start(live_site, browser, scenario())
    page = story.page
    page.get_by_role("list", name="Messages").get_by_role("listitem").first.get_by_role(
        "link"
    ).click()
    pane = page.get_by_role("toolbar", name="Message actions")
    expect(pane.get_by_role("button", name="Flag", exact=True)).to_be_visible()
    held = []
    # The server flags (and pushes); its answer waits until the menu is open.
    page.route(
        re.compile(r"/flag$"), lambda route: held.append((route, route.fetch(max_redirects=0)))
    )

    pane.get_by_role("button", name="Flag", exact=True).click()
    expect(pane.get_by_role("button", name="Unflag", exact=True)).to_be_visible()  # the push
    pane.get_by_text("Move to", exact=True).click()
    menu = pane.get_by_role("list", name="Move to folder")
    expect(menu).to_be_visible()
    page.evaluate(
        "() => { window.answered = new Promise((done) =>"
        " document.addEventListener('htmx:afterSettle', done, { once: true })); }"
    )
    route, answer = held.pop()
    route.fulfill(response=answer)
    page.evaluate("() => window.answered.then(() => true)")

    expect(menu).to_be_visible()
    expect(pane.get_by_role("button", name="Unflag", exact=True)).to_be_visible()
    menu.get_by_role("button", name="Archive").click()
    expect(page.get_by_role("list", name="Messages").get_by_role("listitem")).to_have_count(2)
    assert [name for name, _ in story.actions()] == ["open_email", "flag", "move"]
