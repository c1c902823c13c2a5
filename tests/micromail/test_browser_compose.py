"""Compose and attachments in Chromium: a file attached from the picker, the draft saved while
typing (nothing typed is lost by walking away), the discard confirmation deleting that draft,
and an attachment previewed over its message and closed with Escape. Every change is a logged
action, so the run's log says exactly what the user did."""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import Page, expect

from tests.browser_story import BrowserStory

# tests/micromail/conftest.py binds `browser` to a django.test.Client; this module needs the
# Chromium one from tests/conftest.py.
from tests.conftest import browser  # noqa: F401
from tests.micromail.cast import inbox_scenario

pytestmark = pytest.mark.browser

WAIT_MS = 15000  # a busy machine: generous, never a speed assertion
WITH_ATTACHMENTS = "cc-att-02"  # "Capacity plan": capacity-plan-q3.xlsx, oncall-load-summary.pdf


def scenario() -> dict:
    return inbox_scenario(
        "browser-micromail-compose", "Write to Maya.", [WITH_ATTACHMENTS, "base-01"]
    )


def folder(page: Page, title: str):
    return page.get_by_role("navigation", name="Folders").get_by_role(
        "link", name=re.compile(rf"^{title}\b")
    )


def test_attach_autosave_discard_and_preview(live_site, browser):  # noqa: F811
    story = BrowserStory.start(live_site, browser, scenario())
    page = story.page
    expect(page.get_by_role("heading", level=1, name="Inbox")).to_be_visible(timeout=WAIT_MS)

    # Write a message with an attachment from the picker, then walk away without saving.
    page.get_by_role("link", name="New mail").click()
    expect(page.get_by_role("heading", level=1, name="New message")).to_be_visible(timeout=WAIT_MS)
    page.get_by_role("textbox", name="To").fill("maya.okonjo@example.com")
    page.get_by_role("textbox", name="Subject").fill("Capacity numbers")
    page.get_by_text("Attach file").click()
    page.get_by_role("checkbox", name=re.compile("capacity-plan-q3.xlsx")).check()
    expect(page.get_by_role("list", name="Attached files")).to_contain_text("capacity-plan-q3.xlsx")
    page.get_by_role("textbox", name="Message").fill("Numbers attached.")
    folder(page, "Inbox").click()
    expect(page.get_by_role("heading", level=1, name="Inbox")).to_be_visible(timeout=WAIT_MS)

    # The draft kept it all, in one draft however many times it was saved.
    folder(page, "Drafts").click()
    draft = page.get_by_role("list", name="Messages").get_by_role(
        "link", name=re.compile("Capacity numbers")
    )
    expect(draft).to_have_count(1, timeout=WAIT_MS)
    draft.click()
    expect(page.get_by_role("textbox", name="Message")).to_have_value("Numbers attached.")
    expect(page.get_by_role("list", name="Attached files")).to_contain_text("capacity-plan-q3.xlsx")
    saves = [payload for name, payload in story.actions() if name == "save_draft"]
    assert saves and {p["id"] for p in saves} == {saves[0]["id"]}
    assert saves[-1]["attachments"] == ["att-029"]  # capacity-plan-q3.xlsx

    # Discard asks first; Keep editing keeps the text; Discard deletes the draft.
    discard = page.get_by_role("group", name="Compose actions").get_by_role(
        "button", name="Discard"
    )
    discard.click()
    dialog = page.get_by_role("alertdialog", name="Discard draft?")
    expect(dialog).to_be_visible()
    dialog.get_by_role("button", name="Keep editing").click()
    expect(dialog).to_be_hidden()
    expect(page.get_by_role("textbox", name="Subject")).to_have_value("Capacity numbers")
    discard.click()
    dialog.get_by_role("button", name="Discard").click()
    expect(page.get_by_role("heading", level=1, name="Inbox")).to_be_visible(timeout=WAIT_MS)
    folder(page, "Drafts").click()
    expect(page.get_by_text("Nothing in Drafts.")).to_be_visible(timeout=WAIT_MS)
    name, payload = story.actions()[-1]
    assert (name, payload["permanent"]) == ("delete", True)

    # An attachment opens over its message at its own URL; Escape closes it.
    folder(page, "Inbox").click()
    page.get_by_role("list", name="Messages").get_by_role(
        "link", name=re.compile("Capacity plan")
    ).click()
    page.get_by_role("link", name=re.compile("Preview oncall-load-summary.pdf")).click()
    preview = page.get_by_role("dialog", name="oncall-load-summary.pdf")
    expect(preview).to_be_visible(timeout=WAIT_MS)
    expect(page).to_have_url(re.compile(r"preview="))
    expect(preview.get_by_role("article", name="Document preview")).to_contain_text("capacity plan")
    page.wait_for_function(
        "document.activeElement && document.activeElement.id === 'preview-close'"
    )
    page.keyboard.press("Escape")
    expect(preview).to_have_count(0, timeout=WAIT_MS)
    expect(page).not_to_have_url(re.compile(r"preview="))
