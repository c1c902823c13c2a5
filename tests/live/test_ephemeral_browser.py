"""Items that go away at their time, in Chromium on the live site: each ephemeral scenario's
item appears in the open page by a push, then goes away at `condition_until` by another, the
page never reloading — MicroChat's message deleted by its sender (Teams' notice in its place),
MicroMail's recalled mail (out of the list; the open reading pane says so), MicroHood's dip
(the price below the level, then recovered), MicroGram's expired story (out of the tray; the open
viewer says it is unavailable), MicroTube's video made private (its open watch page turns
"Video unavailable"; an open playlist keeps its row as "[Private video]"), MicroFy's track
made unavailable (its open page says so), MicroScholar's preprint withdrawn by its authors
(out of the recommendations; its open page says so),
MicroDin's job closed to applications (LinkedIn's "No longer accepting applications" in
place of Apply), MicroHub's pull request someone else closed (Closed, no comment box),
MicroLendar's invitation its organiser cancelled (off the calendar; its open details say so).
What leads to an item follows it too: an open story viewer's arrows skip a story that expired
and reach a new one, and a song made unavailable while it plays stops in the player bar."""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import expect

from tests.browser_story import BrowserStory
from tests.microgram.cast import CAST as GRAM
from tests.microgram.cast import (
    EXPIRES_AT,
    LATE_STORY,
    POSTED_AT,
    SGRANT,
    STORIES,
    TRAY_EVENTS,
)

pytestmark = pytest.mark.browser


def opened(live_site, browser, scenario: str | dict, path: str) -> BrowserStory:
    story = BrowserStory.start(live_site, browser, scenario, open_task=False)
    go_to(story, live_site, path)
    return story


def go_to(story: BrowserStory, live_site: str, path: str) -> None:
    """The run's page `path` (below its root), watched from then on for a reload."""
    story.page.goto(f"{live_site}/r/{story.run['token']}/{path}")
    story.watch_for_reload()


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
    go_to(story, live_site, "micromail/?folder=inbox&email=base-38")
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


def test_an_expired_story_just_leaves_the_tray(live_site, browser):
    story = opened(live_site, browser, "microgram-hquinn-story-ephemeral-active", "microgram/")
    bubble = story.page.locator('#stories a[href$="stories/story-hquinn-new-feature/"]')
    expect(bubble).to_have_count(0)
    story.advance(143.7)
    expect(bubble).to_have_attribute("aria-label", "Story by hquinn, not seen yet")
    story.advance(233.7)
    expect(bubble).to_have_count(0)
    # Her older story stays: only the one that expired went.
    expect(
        story.page.locator('#stories a[href$="stories/story-hquinn-launch-graph/"]')
    ).to_have_count(1)
    story.assert_not_reloaded()


def test_an_open_story_that_expires_says_it_is_unavailable(live_site, browser):
    story = opened(live_site, browser, "microgram-first-story-whose-ephemeral-active", "microgram/")
    story.advance(61.2)
    go_to(story, live_site, "microgram/stories/story-fadeyemi-record-haul/")
    frame = story.page.locator("#story-frame")
    held_then_gone(story, frame, 61.2, "fadeyemi", 151.2, "This story is unavailable.")
    expect(frame.get_by_role("img")).to_have_count(0)


def leads_to(story_id: str) -> re.Pattern:
    """An arrow's href: the viewer of `story_id`."""
    return re.compile(f"/stories/{story_id}/$")


def test_an_open_story_viewers_arrows_skip_an_expired_story_and_reach_a_new_one(live_site, browser):
    tray = {**GRAM.scenario, "id": "browser-microgram-changing-tray", "events": TRAY_EVENTS}
    story = opened(live_site, browser, tray, f"microgram/stories/{SGRANT}/")
    oldest, after_it = STORIES
    viewer = story.page.get_by_role("main", name="Story by sgrant")
    onward = viewer.get_by_role("link", name="Next story")
    back = viewer.get_by_role("link", name="Previous story")
    expect(onward).to_have_attribute("href", leads_to(after_it))
    expect(back).to_have_count(0)
    story.advance(EXPIRES_AT)  # the story after the open one expires: the arrow leads past it
    expect(onward).to_have_attribute("href", leads_to(oldest))
    story.advance(POSTED_AT)  # a new story: the newest, reachable from here
    expect(back).to_have_attribute("href", leads_to(LATE_STORY))
    story.assert_not_reloaded()
    onward.click()
    expect(story.page.get_by_role("main", name="Story by rduarte")).to_be_visible()


def test_a_video_made_private_turns_its_open_watch_page_unavailable(live_site, browser):
    story = opened(live_site, browser, "microtube-pulled-upload-ephemeral-active", "microtube/")
    card = story.page.locator('#home-grid a[href*="v=vid-film-02"]').first
    story.advance(382.5)
    expect(card).to_be_visible()
    story.assert_not_reloaded()
    go_to(story, live_site, "microtube/watch?v=vid-film-02")
    held_then_gone(
        story,
        story.page.locator("#watch-primary"),
        382.5,
        "Developing Colour Film at Home",
        472.5,
        "This video is private.",
    )
    expect(story.page.get_by_role("button", name="Save to Watch later")).to_have_count(0)


def test_a_saved_video_made_private_stays_in_the_open_playlist_as_a_private_video(
    live_site, browser
):
    story = opened(live_site, browser, "microtube-pulled-upload-ephemeral-active", "microtube/")
    story.advance(382.5)
    story.page.get_by_role("link", name="Developing Colour Film at Home").first.click()
    story.page.get_by_role("button", name="Save to Watch later").click()
    expect(story.page.get_by_role("button", name="Remove from Watch later")).to_be_visible()
    go_to(story, live_site, "microtube/playlist?list=WL")
    row = story.page.locator("#playlist-videos article").first
    expect(row).to_contain_text("Developing Colour Film at Home")
    story.advance(472.5)
    expect(row).to_have_attribute("aria-label", "[Private video]")
    story.assert_not_reloaded()
    expect(story.page.locator("#playlist-videos")).not_to_contain_text("Developing Colour Film")
    expect(story.page.locator(".yt-playlist-hero")).to_contain_text("1 video")  # still counted
    row.get_by_role("link", name="[Private video]").click()
    expect(story.page.locator("#watch-primary")).to_contain_text("This video is private.")


def test_a_track_made_unavailable_says_so_on_its_open_page(live_site, browser):
    story = opened(live_site, browser, "microfy-pulled-single-ephemeral-active", "microfy/")
    story.advance(327.8)
    expect(story.page.locator("#trending")).to_contain_text("Secret Stations")
    story.assert_not_reloaded()
    go_to(story, live_site, "microfy/track/track-090")
    held_then_gone(
        story,
        story.page.locator("#track-actions"),
        327.8,
        "Add to playlist",
        417.8,
        "This song is unavailable.",
    )


def test_a_track_made_unavailable_while_it_plays_stops_in_the_open_pages_player(live_site, browser):
    story = opened(live_site, browser, "microfy-pulled-single-ephemeral-active", "microfy/")
    story.advance(327.8)
    go_to(story, live_site, "microfy/track/track-090")
    story.page.get_by_role("button", name="Play Secret Stations", exact=True).click()
    player = story.page.get_by_role("contentinfo", name="Now playing")
    expect(player.get_by_role("link", name="Secret Stations")).to_be_visible()
    expect(player.get_by_role("button", name="Pause")).to_be_visible()
    story.watch_for_reload()
    story.advance(417.8)
    expect(player).to_contain_text("Pick something to play")
    expect(player.get_by_role("link", name="Secret Stations")).to_have_count(0)
    expect(story.page.locator("#track-actions")).to_contain_text("This song is unavailable.")
    story.assert_not_reloaded()


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
    go_to(story, live_site, "microscholar/papers/paper-046")
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


def test_a_closed_job_shows_linkedins_notice_in_place_of_apply(live_site, browser):
    story = opened(
        live_site, browser, "microdin-pm-integrations-ephemeral-active", "microdin/jobs/"
    )
    card = story.page.locator("#job-list li.job-card", has_text="Product Manager, Integrations")
    story.advance(61.8)
    expect(card).to_have_count(1)
    go_to(story, live_site, "microdin/jobs/?job=job-01")
    detail = story.page.locator("#job-detail")
    expect(detail.get_by_role("button", name="Apply")).to_have_count(1)
    held_then_gone(
        story,
        detail,
        61.8,
        "Product Manager, Integrations",
        173.2,
        "No longer accepting applications",
    )
    expect(detail.get_by_role("button", name="Apply")).to_have_count(0)
    expect(card).to_contain_text("No longer accepting applications")


def test_a_pull_request_someone_else_closed_turns_closed_without_a_comment_box(live_site, browser):
    story = opened(live_site, browser, "microhub-board-review-ephemeral-active", "microhub/pulls/")
    story.advance(226.5)
    expect(story.page.locator("#pr-list")).to_contain_text("perf: virtualise board columns")
    go_to(story, live_site, "microhub/pulls/pr5")
    held_then_gone(story, story.page.locator("#pr-state"), 226.5, "Open", 331.0, "Closed")
    expect(story.page.locator("#pr-merge")).to_contain_text("Closed with unmerged commits")
    expect(story.page.get_by_role("form", name="Add a comment")).to_have_count(0)


def test_a_cancelled_invitation_leaves_the_calendar_and_its_open_details_say_so(live_site, browser):
    story = opened(
        live_site,
        browser,
        "microlendar-photo-slot-ephemeral-passive",
        "microlendar/",
    )
    invitations = story.page.locator("#new-invitations")
    story.advance(137.4)
    expect(invitations).to_contain_text("DevSummit West speaker photos")
    go_to(story, live_site, "microlendar/?event=slot-01")
    held_then_gone(
        story,
        story.page.locator("#event-details"),
        137.4,
        "Astrid",
        242.9,
        "This event has been canceled",
    )
    expect(invitations).not_to_contain_text("DevSummit West speaker photos")
