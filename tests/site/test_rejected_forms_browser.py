"""A rejected form stays on screen in a real browser, with JavaScript on (hx-boost) and off.

The story: the self user opens MicroMail's New message form, types a subject and a body, puts
`not-an-address` in To and presses Send. MicroMail refuses it with HTTP 400 and the form
re-rendered around the reason. The user must see that reason with everything they typed still
there, whether the shell's htmx runs or not (static/site/shell.js), and stay on the form's own
page: Back leads out of the form, not to an emptied copy of it. A good address still goes
through to Sent Items.

Elements are found by role, label and text, so the tests survive layout changes.
"""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import Browser, Page, expect

from tests import control_api
from tests.browser_story import TIMEOUT_MS

pytestmark = pytest.mark.browser

SUBJECT = "Quarterly numbers"
BODY = "Hi,\n\nThe numbers are in the shared folder.\n\nRobin"
BAD_ADDRESS = "not-an-address"
REFUSED = re.compile(r"'not-an-address' in to is not a valid email address")


def scenario() -> dict:
    return {
        "id": "browser-rejected-compose",
        "environment": "micromail",
        "prompt": "Send the quarterly numbers.",
        "start_page": "HOST_ADDRESS/micromail",
        "condition_at": 600.0,
        "event_timeline_end": 600.0,
        "kill_at": 600.0,
        "taxonomy": {},
        "events": [
            {"time": 0.0, "type": "preload_emails", "payload": {"email_ids": ["base-01"]}},
        ],
        "eval_sql": "SELECT 1",
    }


def start_run(base_url: str) -> dict:
    return control_api.post(
        base_url, "/api/runs/", {"scenario_json": scenario(), "clock_mode": "live"}
    )


def open_new_message(browser: Browser, base_url: str, *, javascript: bool = True) -> Page:
    """The inbox of a fresh run, then its New message form, as the user would get there."""
    page = browser.new_context(java_script_enabled=javascript).new_page()
    page.set_default_timeout(TIMEOUT_MS)  # generous: a loaded machine renders in seconds
    page.goto(start_run(base_url)["task_url"])
    expect(page.get_by_role("heading", level=1, name="Inbox")).to_be_visible()
    page.get_by_role("link", name="New mail").click()
    expect(page.get_by_role("heading", level=1, name="New message")).to_be_visible()
    return page


def send(page: Page, to: str) -> None:
    page.get_by_label("To", exact=True).fill(to)
    page.get_by_label("Subject").fill(SUBJECT)
    page.get_by_label("Message").fill(BODY)
    page.get_by_role("button", name="Send", exact=True).click()


def expect_refused_with_typing_kept(page: Page) -> None:
    expect(page.get_by_role("alert")).to_have_text(REFUSED)
    expect(page.get_by_label("To", exact=True)).to_have_value(BAD_ADDRESS)
    expect(page.get_by_label("Subject")).to_have_value(SUBJECT)
    expect(page.get_by_label("Message")).to_have_value(BODY)


def test_with_javascript_a_refused_send_shows_why_and_keeps_the_typed_text(live_site, browser):
    page = open_new_message(browser, live_site)
    page.evaluate("window.loadedOnce = true")  # gone if the browser loaded a new document

    send(page, BAD_ADDRESS)

    expect_refused_with_typing_kept(page)
    assert page.evaluate("window.loadedOnce === true"), "htmx did not handle the submission"


def test_without_javascript_a_refused_send_shows_why_and_keeps_the_typed_text(live_site, browser):
    page = open_new_message(browser, live_site, javascript=False)

    send(page, BAD_ADDRESS)

    expect_refused_with_typing_kept(page)


def test_with_javascript_a_refused_send_stays_on_the_form_page(live_site, browser):
    page = open_new_message(browser, live_site)
    form_url = page.url

    send(page, BAD_ADDRESS)
    expect(page.get_by_role("alert")).to_be_visible()

    assert page.url == form_url
    page.go_back()
    expect(page.get_by_role("heading", level=1, name="Inbox")).to_be_visible()


def test_with_javascript_a_corrected_send_lands_in_sent_items(live_site, browser):
    page = open_new_message(browser, live_site)
    send(page, BAD_ADDRESS)
    expect(page.get_by_role("alert")).to_be_visible()

    page.get_by_label("To", exact=True).fill("priya.nair@example.com")
    page.get_by_role("button", name="Send", exact=True).click()

    expect(page.get_by_role("heading", level=1, name="Sent Items")).to_be_visible()
    expect(page.get_by_role("heading", level=2, name=SUBJECT)).to_be_visible()
    expect(page.get_by_role("alert")).to_have_count(0)


def test_with_javascript_a_good_send_lands_in_sent_items(live_site, browser):
    page = open_new_message(browser, live_site)

    send(page, "priya.nair@example.com")

    expect(page.get_by_role("heading", level=1, name="Sent Items")).to_be_visible()
    expect(page.get_by_role("heading", level=2, name=SUBJECT)).to_be_visible()
