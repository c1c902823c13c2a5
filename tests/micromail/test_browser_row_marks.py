"""A row's marks sit on its subject line, as in Outlook: a high-importance message shows a small
red "!" at the right of its subject, not an arrow on a line of its own (issue #28)."""

from __future__ import annotations

import pytest
from playwright.sync_api import Page, expect

from tests.browser_story import BrowserStory

# tests/micromail/conftest.py binds `browser` to a django.test.Client; this module needs the
# Chromium one from tests/conftest.py.
from tests.conftest import browser  # noqa: F401
from tests.micromail.cast import inbox_scenario

pytestmark = pytest.mark.browser

URGENT = "urg-03"  # "Need launch go/no-go by 3pm", high importance
ORDINARY = "base-40"  # "Partner sync recap", no marks


def scenario() -> dict:
    return inbox_scenario(
        "browser-micromail-row-marks", "Read the urgent mail.", [URGENT, ORDINARY]
    )


def box(page: Page, email_id: str, selector: str) -> dict:
    row = page.locator("li.message").filter(has=page.locator(f'input[value="{email_id}"]'))
    return row.locator(selector).bounding_box()


def test_high_importance_is_a_red_exclamation_on_the_subject_line(live_site, browser):  # noqa: F811
    page = BrowserStory.start(live_site, browser, scenario()).page
    mark = page.get_by_role("img", name="High importance")
    expect(mark).to_be_visible()
    assert mark.locator("use").get_attribute("href") == "#icon-exclamation-mark"
    assert mark.evaluate("m => getComputedStyle(m).color") == "rgb(197, 15, 31)"  # Outlook's red

    subject, drawn = box(page, URGENT, ".subject"), mark.bounding_box()
    assert drawn["x"] > subject["x"] + subject["width"] - 1  # at the subject's right
    middle = drawn["y"] + drawn["height"] / 2
    assert subject["y"] <= middle <= subject["y"] + subject["height"]  # on its line
    # So the row is no taller than a row without marks: sender, subject, preview.
    assert box(page, URGENT, "a.row-link")["height"] == box(page, ORDINARY, "a.row-link")["height"]
