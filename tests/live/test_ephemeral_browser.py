"""Items that go away at their time, in Chromium on the live site: each ephemeral scenario's
item appears in the open page by a push, then goes away at `condition_until` by another, the
page never reloading — MicroChat's message deleted by its sender (Teams' notice in its place),
MicroMail's recalled mail (out of the list; the open reading pane says so), MicroHood's dip
(the price below the level, then recovered), MicroScholar's preprint withdrawn by its authors
(out of the recommendations; its open page says so)."""

from __future__ import annotations

import pytest
from playwright.sync_api import expect

from tests.browser_story import BrowserStory

pytestmark = pytest.mark.browser


def opened(live_site, browser, scenario: str, path: str) -> BrowserStory:
    story = BrowserStory.start(live_site, browser, scenario, open_task=False)
    story.page.goto(f"{live_site}/r/{story.run['token']}/{path}")
    story.watch_for_reload()
    return story


def held_then_gone(story: BrowserStory, region, at: float, shown: str, until: float, gone: str):
    """The page's `region` shows `shown` once the clock passes `at`, then `gone` once it passes
    `until`: both pushed, the page never reloading."""
    story.advance(at)
    expect(region).to_contain_text(shown)
    story.advance(until)
    expect(region).to_contain_text(gone)
    story.assert_not_reloaded()


def test_a_chat_message_deleted_by_its_sender_is_replaced_by_teams_notice(live_site, browser):
    story = opened(
        live_site,
        browser,
        "microchat-unsent-build-ephemeral-active",
        "microchat/?conversation=direct-hana",
    )
    message = story.page.locator("#msg-dm-hana-06")
    expect(message).to_have_count(0)
    held_then_gone(
        story, message, 402.0, "New TestFlight build is up", 492.0, "This message has been deleted."
    )
    expect(message).not_to_contain_text("TestFlight")
    expect(message.get_by_role("group", name="Message options")).to_have_count(0)


def test_a_recalled_mail_leaves_the_list_and_its_open_reading_pane_says_so(live_site, browser):
    story = opened(
        live_site, browser, "micromail-recalled-payroll-ephemeral-active", "micromail/?folder=inbox"
    )
    row = story.page.locator('#message-list a.row-link[href*="email=base-38"]')
    story.advance(288.4)
    expect(row).to_have_count(1)
    story.assert_not_reloaded()
    story.page.goto(f"{live_site}/r/{story.run['token']}/micromail/?folder=inbox&email=base-38")
    story.watch_for_reload()
    held_then_gone(
        story,
        story.page.locator("#reading-pane"),
        288.4,
        "Payroll date shift for the long weekend",
        397.6,
        "The sender recalled this message.",
    )
    expect(row).to_have_count(0)


def test_a_dip_shows_below_the_level_then_recovered(live_site, browser):
    story = opened(
        live_site, browser, "microhood-orch-dip-ephemeral-active", "microhood/stocks/ORCH"
    )
    main = story.page.locator("main")
    held_then_gone(story, main, 390.0, "$177.20", 520.0, "$184.50")
    expect(main).to_contain_text("Today's low$177.2")  # the dip, in the day's range


def test_a_withdrawn_preprint_leaves_the_recommendations_and_its_open_page_says_so(
    live_site, browser
):
    story = opened(
        live_site, browser, "microscholar-withdrawn-preprint-ephemeral-active", "microscholar/"
    )
    entry = story.page.locator("#recommended li.result", has=story.page.locator("#t-paper-046"))
    expect(entry).to_have_count(0)
    story.advance(327.4)
    expect(entry).to_have_count(1)
    story.assert_not_reloaded()
    story.page.goto(f"{live_site}/r/{story.run['token']}/microscholar/papers/paper-046")
    story.watch_for_reload()
    paper = story.page.locator("#paper")
    held_then_gone(
        story,
        paper,
        327.4,
        "Save to My library",
        421.9,
        "This paper has been withdrawn by its authors.",
    )
    expect(paper).to_contain_text("Long-Horizon Evaluation of Monitoring Agents")  # title kept
    expect(paper.get_by_role("group", name="Actions for this paper")).to_have_count(0)
    story.page.goto(f"{live_site}/r/{story.run['token']}/microscholar/")
    expect(story.page.locator("#recommended")).to_contain_text("Asking Before Acting")
    expect(entry).to_have_count(0)
