"""MicroTube in a real browser: a channel's upload is pushed into the open Subscriptions feed,
and the user opens it and likes it.

The story: the self user opens the task URL of the Trailhead Tales scenario and goes to
Subscriptions. The harness moves the virtual clock to the moment Trailhead Tales uploads; the
video appears at the top of the open feed, and the bell's badge goes up (Wayfarer Notes'
notification came in on the way), without a reload. The
user opens the video (that is watching it), likes it, and reports back. The grade sees exactly
those two actions.

Elements are found by role, label and text, so the test survives layout changes.
"""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import expect

from tests.browser_story import BrowserStory

pytestmark = pytest.mark.browser

SCENARIO = "microtube-video-absolute-active"
UPLOADED_AT = 516.0
TITLE = "Sunrise on Mount Pilchuck: A Winter Day Hike"
VIDEO = "vid-trail-03"


def test_a_pushed_upload_is_opened_and_liked(live_site, browser):
    story = BrowserStory.start(live_site, browser, SCENARIO)
    page = story.page
    guide = page.get_by_role("navigation", name="Guide")
    guide.get_by_role("link", name="Subscriptions", exact=True).click()
    feed = page.get_by_label("Latest videos from your subscriptions")
    expect(feed.get_by_role("link", name="Three Days on the Olympic Coast Trail")).to_be_visible()
    expect(feed.get_by_role("link", name=TITLE)).to_have_count(0)
    expect(page.get_by_label("Notifications (5 unread)")).to_be_visible()
    story.watch_for_reload()

    story.advance(UPLOADED_AT)
    expect(feed.get_by_role("article").first).to_have_attribute("aria-label", TITLE)
    expect(page.get_by_label("Notifications (7 unread)")).to_be_visible()
    story.assert_not_reloaded()

    feed.get_by_role("link", name=TITLE).click()
    expect(page.get_by_role("heading", level=1, name=TITLE)).to_be_visible()
    expect(page.get_by_role("figure", name=re.compile("^Video player"))).to_be_visible()
    page.get_by_role("button", name=re.compile(r"^Like this video")).click()
    expect(page.get_by_role("button", name=re.compile(r"^Remove like"))).to_be_visible()

    assert story.report() == [
        ("watch_video", {"video_id": VIDEO}),
        ("like_video", {"video_id": VIDEO}),
    ]
