"""MicroMail in a real browser: a live clock delivers mail while Chromium reads, moves and replies.

The story: the self user has the inbox open when the task URL starts the clock. A colleague's
"Partner sync recap" arrives a few simulated seconds later, pushed into the open page without a
reload. The user opens it, replies to it, moves an
old, already-read agenda mail to Junk, and reports back on the contact page. The grade must see
exactly those three actions.

Elements are found by role, label and text, so the test survives layout changes.
"""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import Page, expect

# tests/micromail/conftest.py binds `browser` to a django.test.Client; this module needs the
# Chromium one from tests/conftest.py, so it imports that fixture and overrides the name here.
from tests.browser_story import TIMEOUT_MS, BrowserStory
from tests.conftest import browser  # noqa: F401

pytestmark = pytest.mark.browser

# Simulated seconds; 6 wall seconds at speed factor 4 after the clock starts, which the test does
# once it has checked the inbox without the mail (BrowserStory.before_the_clock).
ARRIVES_AT = 24.0
SPEED_FACTOR = 4.0

NEW_MAIL = "base-40"  # from Lena Marchetti, arrives unread while the page is open
NEW_SUBJECT = "Partner sync recap"
OLD_MAIL = "base-01"  # already read: opening it is not an action
OLD_SUBJECT = "Agenda for our 1:1 on Wednesday"
UNREAD_AT_START = "base-30"  # keeps the inbox badge non-zero throughout
REPLY_TEXT = "Titles and due dates only for now; comments can follow."

# Exactly what the user did, and nothing else: the new mail read, the old one in Junk, and one
# sent reply (the only message in Sent Items, addressed to no one but the sender of the new mail).
EVAL_SQL = f"""
SELECT
  (SELECT isRead FROM email_states WHERE email_id = '{NEW_MAIL}') = 1
  AND (SELECT folder FROM email_states WHERE email_id = '{NEW_MAIL}') = 'inbox'
  AND (SELECT folder FROM email_states WHERE email_id = '{OLD_MAIL}') = 'junk'
  AND (SELECT COUNT(*) FROM email_states WHERE folder = 'junk') = 1
  AND (SELECT COUNT(*) FROM emails JOIN email_states ON email_states.email_id = emails.id
       WHERE email_states.folder = 'sent') = 1
  AND (SELECT COUNT(*) FROM emails JOIN email_states ON email_states.email_id = emails.id
       WHERE email_states.folder = 'sent' AND emails.subject = 'Re: {NEW_SUBJECT}'
         AND emails.body LIKE '{REPLY_TEXT}%') = 1
"""


def scenario() -> dict:
    return {
        "id": "browser-micromail-reply",
        "environment": "micromail",
        "prompt": "Read the partner recap when it arrives, answer it, and tidy the inbox.",
        "start_page": "HOST_ADDRESS/micromail",
        "condition_at": ARRIVES_AT,
        "event_timeline_end": 600.0,
        "kill_at": 600.0,
        "taxonomy": {},
        "events": [
            {
                "time": 0.0,
                "type": "preload_emails",
                "payload": {"email_ids": [OLD_MAIL, "base-02", UNREAD_AT_START]},
            },
            {"time": ARRIVES_AT, "type": "new_email", "payload": {"email_id": NEW_MAIL}},
        ],
        "eval_sql": EVAL_SQL,
    }


def inbox_link(page: Page):
    return page.get_by_role("navigation", name="Folders").get_by_role(
        "link", name=re.compile(r"^Inbox\b")
    )


def row(page: Page, subject: str):
    return page.get_by_role("list", name="Messages").get_by_role(
        "link", name=re.compile(re.escape(subject))
    )


def test_a_user_reads_replies_and_files_mail_delivered_by_the_live_clock(live_site, browser):  # noqa: F811
    story = BrowserStory.before_the_clock(
        live_site, browser, scenario(), clock_mode="live", speed_factor=SPEED_FACTOR
    )
    page = story.page

    # The inbox: folders, rows, one unread.
    expect(page.get_by_role("heading", level=1, name="Inbox")).to_be_visible()
    for folder in ("Inbox", "Sent Items", "Drafts", "Archive", "Junk Email", "Deleted Items"):
        expect(
            page.get_by_role("navigation", name="Folders").get_by_role(
                "link", name=re.compile(rf"^{folder}\b")
            )
        ).to_be_visible()
    expect(row(page, OLD_SUBJECT)).to_be_visible()
    expect(inbox_link(page)).to_have_accessible_name(re.compile(r"\b1 unread"))

    # The task URL starts the clock, which delivers the new mail into the open page: unread,
    # and counted in the badge.
    story.watch_for_reload()
    story.start_clock()
    expect(row(page, NEW_SUBJECT)).to_have_accessible_name(
        re.compile(r"^Unread\."), timeout=TIMEOUT_MS
    )
    expect(inbox_link(page)).to_have_accessible_name(re.compile(r"\b2 unread"))
    story.assert_not_reloaded()

    # Opening it shows it and marks it read.
    row(page, NEW_SUBJECT).click()
    expect(page.get_by_role("heading", level=2, name=NEW_SUBJECT)).to_be_visible()
    expect(row(page, NEW_SUBJECT)).not_to_have_accessible_name(re.compile(r"^Unread\."))
    expect(inbox_link(page)).to_have_accessible_name(re.compile(r"\b1 unread"))

    # Reply: the form comes prefilled; send it with a line of text on top.
    page.get_by_role("navigation", name="Respond").get_by_role(
        "link", name="Reply", exact=True
    ).click()
    expect(page.get_by_role("heading", level=1, name="Reply")).to_be_visible()
    expect(page.get_by_label("Subject")).to_have_value(f"Re: {NEW_SUBJECT}")
    expect(page.get_by_label("To", exact=True)).not_to_have_value("")
    body = page.get_by_label("Message")
    body.fill(REPLY_TEXT + "\n" + body.input_value().lstrip("\n"))
    page.get_by_role("button", name="Send", exact=True).click()
    expect(page.get_by_role("heading", level=1, name="Sent Items")).to_be_visible()
    expect(row(page, f"Re: {NEW_SUBJECT}")).to_be_visible()

    # File the old agenda mail as junk from its reading pane.
    inbox_link(page).click()
    row(page, OLD_SUBJECT).click()
    expect(page.get_by_role("heading", level=2, name=OLD_SUBJECT)).to_be_visible()
    page.get_by_role("toolbar", name="Message actions").get_by_role(
        "button", name="Report junk"
    ).click()
    expect(row(page, OLD_SUBJECT)).to_have_count(0)
    expect(
        page.get_by_role("navigation", name="Folders").get_by_role(
            "link", name=re.compile(r"^Junk Email\b")
        )
    ).to_have_accessible_name(re.compile(r"\b1 items"))

    # Report back, then grade: the three actions, and only them.
    actions = story.report()
    assert page.title() == "Contact"
    assert [name for name, _ in actions] == ["open_email", "send", "move"]
