"""MicroScholar in a real browser: the clock indexes the awaited paper while Chromium watches.

The story: the self user opens the task URL on the home page with its recommended articles.
"Deliberate Delegation" is indexed when the clock reaches it and shows up in the list without a
reload (a live push). The user opens its Cite dialog (which cites it), reads the MLA line,
closes it, saves the paper, and reports back. The grade must see exactly those two actions.
"""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import Page, expect

from tests.browser_story import BrowserStory
from tests.conftest import browser  # noqa: F401  (the Chromium fixture)
from tests.microscholar.cast import CAST, TARGET_AT
from tests.microscholar.cast import TARGET_TITLE as TITLE

pytestmark = pytest.mark.browser


def recommended(page: Page):
    return page.get_by_role("list", name="Recommended articles")


def test_a_user_sees_the_paper_arrive_live_then_cites_and_saves_it(live_site, browser):  # noqa: F811
    story = BrowserStory.start(live_site, browser, dict(CAST.scenario))
    page = story.page

    expect(page.get_by_role("heading", name=re.compile("Recommended articles"))).to_be_visible()
    expect(
        recommended(page).get_by_role(
            "link", name="Faithfulness Checks for Abstractive Meeting Summaries", exact=True
        )
    ).to_be_visible()
    expect(recommended(page).get_by_role("link", name=TITLE, exact=True)).to_have_count(0)

    # Indexed by the clock and pushed into the open page: no reload.
    story.watch_for_reload()
    story.advance(TARGET_AT)
    expect(recommended(page).get_by_role("link", name=TITLE, exact=True)).to_be_visible()
    expect(page.get_by_role("heading", name=re.compile("4 articles"))).to_be_visible()
    story.assert_not_reloaded()

    # The Cite dialog: opening it cites the paper; it shows the five styles.
    page.get_by_role("link", name=f"Cite {TITLE}").click()
    dialog = page.get_by_role("dialog", name="Cite")
    expect(dialog).to_be_visible()
    styles = dialog.get_by_role("table", name="Citation styles")
    for style in ("MLA", "APA", "Chicago", "Harvard", "BibTeX"):
        expect(styles.get_by_role("rowheader", name=style)).to_be_visible()
    expect(styles).to_contain_text('Park, Yuna, et al. "Deliberate Delegation')
    dialog.get_by_role("link", name="Close").click()

    # Save it from the paper page; the library counts it.
    page.get_by_role("button", name="Save to My library").click()
    expect(page.get_by_role("button", name=re.compile("Saved"))).to_be_visible()
    expect(
        page.get_by_role("navigation", name="My Scholar").get_by_role(
            "link", name=re.compile("My library 1")
        )
    ).to_be_visible()

    page.goto(story.run["contact_url"])
    verdict = story.api("POST", f"/api/runs/{story.run['id']}/evaluate/")
    assert verdict["success"] is True, verdict["detail"]
    assert verdict["actions"] == 2
    assert [name for name, _ in story.actions()] == ["cite", "save"]


def test_nonsense_finds_nothing_and_a_topic_finds_its_papers_best_first(live_site, browser):  # noqa: F811
    """Finding: "zzqqxxnothing" listed 18 papers (the original's three-letter shingles)."""
    story = BrowserStory.start(live_site, browser, dict(CAST.scenario))
    page = story.page
    search = page.get_by_role("search", name="Search articles").get_by_role("searchbox")

    search.fill("zzqqxxnothing")
    search.press("Enter")
    expect(page.get_by_text("did not match any articles")).to_be_visible()
    expect(page.get_by_role("list", name="Search results")).to_have_count(0)

    search = page.get_by_role("search", name="Search articles").get_by_role("searchbox")
    search.fill("meeting summaries")
    search.press("Enter")
    results = page.get_by_role("list", name="Search results")
    expect(results.get_by_role("listitem").first).to_contain_text("Meeting Summaries")
    expect(page.get_by_text("did not match any articles")).to_have_count(0)
