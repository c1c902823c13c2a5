"""MicroGram in a real browser: a live clock delivers Marco's desk post while Chromium watches
the feed, which shows it on top without a reload; the user likes it with the heart, opens it,
and reports back. The grade must see exactly those actions.

Elements are found by role and accessible name, so the test survives layout changes.
"""

from __future__ import annotations

import pytest
from playwright.sync_api import expect

from tests.browser_story import BrowserStory
from tests.microgram.cast import DESK, PRELOAD

pytestmark = pytest.mark.browser

ARRIVES_AT = 20.0  # simulated seconds; 5 wall seconds at speed factor 4 after the clock starts
SPEED_FACTOR = 4.0


def scenario() -> dict:
    return {
        "id": "browser-microgram-like",
        "environment": "microgram",
        "prompt": "Like Marco's desk post when it shows up.",
        "start_page": "HOST_ADDRESS/microgram",
        "condition_at": ARRIVES_AT,
        "event_timeline_end": 600.0,
        "kill_at": 600.0,
        "taxonomy": {},
        "events": [
            {"time": 0.0, "type": "preload_posts", "payload": PRELOAD},
            {"time": ARRIVES_AT, "type": "new_post", "payload": {"post_id": DESK}},
        ],
        "eval_sql": f"SELECT (SELECT isLiked FROM post_states WHERE post_id = '{DESK}') = 1",
    }


def test_a_post_arrives_live_and_is_liked_with_the_heart(live_site, browser):
    story = BrowserStory.before_the_clock(
        live_site, browser, scenario(), clock_mode="live", speed_factor=SPEED_FACTOR
    )
    page = story.page

    feed = page.get_by_role("main", name="Home")
    expect(feed.get_by_role("article", name="Post by nhaddad")).to_be_visible()
    expect(feed.get_by_role("article", name="Post by mbellini")).to_have_count(0)

    # The task URL starts the clock; the post arrives: it is pushed into the feed, on top,
    # without a reload.
    story.watch_for_reload()
    story.start_clock()
    marco = feed.get_by_role("article", name="Post by mbellini")
    expect(marco).to_be_visible()
    expect(feed.get_by_role("article").first).to_have_accessible_name("Post by mbellini")
    story.assert_not_reloaded()

    # Like it with the heart; the heart turns into "Unlike" and the count moves.
    marco.get_by_role("button", name="Like post by mbellini").click()
    expect(marco.get_by_role("button", name="Unlike post by mbellini")).to_be_visible()

    # Open it from "View all 5 comments": the post page lists the five comments.
    marco.get_by_role("link", name="View all 5 comments").click()
    expect(page.get_by_role("list", name="Comments").get_by_role("listitem")).to_have_count(5)

    assert [name for name, _ in story.report()] == ["like_post", "view_post"]
