"""MicroChat in a real browser: a live clock delivers Gabriel's urgent message while Chromium
watches the chat list, which updates without a reload; the user opens the chat (reading it),
likes the message and reports back. The grade must see exactly those two actions.

Elements are found by role, label and text, so the test survives layout changes.
"""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import Page, expect

from tests.browser_story import TIMEOUT_MS, BrowserStory

# The Chromium `browser` fixture of tests/conftest.py (imported so the name is this module's).
from tests.conftest import browser  # noqa: F401

pytestmark = pytest.mark.browser

ARRIVES_AT = 20.0  # simulated seconds; 5 wall seconds at speed factor 4 after the clock starts
SPEED_FACTOR = 4.0
URGENT = "urg-gabriel-09"

EVAL_SQL = f"""
SELECT (SELECT isRead FROM message_states WHERE message_id = '{URGENT}') = 1
  AND (SELECT COUNT(*) FROM message_states WHERE isRead = 0) = 0
"""


def scenario() -> dict:
    return {
        "id": "browser-microchat-payments",
        "environment": "microchat",
        "prompt": "Read Gabriel's payment alert when it arrives.",
        "start_page": "HOST_ADDRESS/microchat",
        "condition_at": ARRIVES_AT,
        "event_timeline_end": 600.0,
        "kill_at": 600.0,
        "taxonomy": {},
        "events": [
            {
                "time": 0.0,
                "type": "preload_messages",
                "payload": {"message_ids": ["dm-gabriel-01", "dm-gabriel-02", "dm-maya-01"]},
            },
            {"time": ARRIVES_AT, "type": "new_message", "payload": {"message_id": URGENT}},
        ],
        "eval_sql": EVAL_SQL,
    }


def chat_row(page: Page, name: str):
    return page.get_by_role("list", name="Chats").get_by_role(
        "link", name=re.compile(rf"^(Unread: )?{re.escape(name)}\b")
    )


def test_a_user_sees_a_message_arrive_live_and_reads_and_likes_it(live_site, browser):  # noqa: F811
    story = BrowserStory.before_the_clock(
        live_site, browser, scenario(), clock_mode="live", speed_factor=SPEED_FACTOR
    )
    page = story.page

    # The chat list, Gabriel's chat already read.
    expect(page.get_by_role("heading", level=1, name="Chat")).to_be_visible()
    expect(chat_row(page, "Gabriel Nwosu")).not_to_have_accessible_name(re.compile("^Unread:"))

    # The task URL starts the clock; the urgent message arrives: the row turns unread in place,
    # without a reload.
    story.watch_for_reload()
    story.start_clock()
    expect(chat_row(page, "Gabriel Nwosu")).to_have_accessible_name(
        re.compile(r"^Unread: Gabriel Nwosu.*card payments are failing"), timeout=TIMEOUT_MS
    )
    expect(
        page.get_by_role("navigation", name="Apps").get_by_role("link", name=re.compile("^Chat"))
    ).to_have_accessible_name(re.compile(r"1 unread chat"))
    story.assert_not_reloaded()

    # Opening the chat shows the message with its urgent marker and reads it.
    chat_row(page, "Gabriel Nwosu").click()
    expect(page.get_by_role("heading", level=2, name="Gabriel Nwosu")).to_be_visible()
    message = page.get_by_role("article", name=re.compile(r"^Gabriel Nwosu, .*urgent$"))
    expect(message).to_contain_text("card payments are failing")
    expect(message).to_contain_text("URGENT!")
    expect(chat_row(page, "Gabriel Nwosu")).not_to_have_accessible_name(re.compile("^Unread:"))

    # Like it from the message's hover toolbar.
    message.hover()
    page.get_by_role("group", name="Message options").get_by_role(
        "button", name="React Like"
    ).last.click()
    expect(
        page.get_by_role("list", name="Reactions").get_by_role("button")
    ).to_have_accessible_name(re.compile(r"^Like 1: You"))

    # Report back, then grade: the two actions, and only them.
    assert [name for name, _ in story.report()] == ["open_conversation", "react"]


def test_a_chats_marks_sit_after_its_name_never_over_it(live_site, browser):  # noqa: F811
    """Finding: the muted and meeting icons were drawn over the chat's name."""
    story = BrowserStory.start(live_site, browser, "microchat-attachment-absolute-active")
    page = story.page
    row = page.locator("li.row").filter(has=page.get_by_role("img", name="Meeting chat")).first
    mark, name = row.get_by_role("img", name="Meeting chat"), row.locator(".row-name")
    mark_box, name_box = mark.bounding_box(), name.bounding_box()
    assert mark_box is not None and name_box is not None
    assert mark_box["x"] >= name_box["x"] + name_box["width"]  # after the (cut) name
    assert abs(mark_box["y"] - name_box["y"]) < name_box["height"]  # on its line
