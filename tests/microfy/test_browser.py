"""MicroFy in a real browser: the clock drops a new song into the trending feed while Chromium
watches the home page, which updates without a reload; the user opens the song, reads its
lyrics, likes it and plays it, and reports back. The grade must see exactly those actions.

Elements are found by role, label and text, so the test survives layout changes.
"""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import Page, expect

from tests.browser_story import BrowserStory

# The Chromium `browser` fixture of tests/conftest.py (imported so the name is this module's).
from tests.conftest import browser  # noqa: F401
from tests.microfy.cast import FIRST_TEN, SLOW_HARBOR

pytestmark = pytest.mark.browser

ARRIVES_AT = 20.0  # simulated seconds
SONG = SLOW_HARBOR

EVAL_SQL = f"""
SELECT (SELECT isLiked FROM track_states WHERE track_id = '{SONG}') = 1
  AND (SELECT userPlayCount FROM track_states WHERE track_id = '{SONG}') = 1
"""


def scenario() -> dict:
    return {
        "id": "browser-microfy-lighthouse",
        "environment": "microfy",
        "prompt": "Like and play the new song that mentions a lighthouse.",
        "start_page": "HOST_ADDRESS/microfy",
        "condition_at": ARRIVES_AT,
        "event_timeline_end": 600.0,
        "kill_at": 600.0,
        "taxonomy": {},
        "events": [
            {
                "time": 0.0,
                "type": "preload_tracks",
                "payload": {
                    "track_ids": FIRST_TEN,
                    "playlist_ids": ["playlist-001", "playlist-002"],
                    "mood_ids": ["*"],
                },
            },
            {"time": ARRIVES_AT, "type": "new_track", "payload": {"track_id": SONG}},
        ],
        "eval_sql": EVAL_SQL,
    }


def trending(page: Page):
    return page.get_by_role("list", name="Trending songs, newest first")


def test_a_user_sees_a_song_drop_live_and_likes_and_plays_it(live_site, browser):  # noqa: F811
    story = BrowserStory.start(live_site, browser, scenario())
    page = story.page
    expect(page.get_by_role("heading", name=re.compile("^Trending Songs"))).to_be_visible()
    expect(trending(page).get_by_role("link", name="Slow Harbor by Neon Pilgrims")).to_have_count(0)

    # The song drops: it appears first in the trending row in place, without a reload.
    story.watch_for_reload()
    story.advance(ARRIVES_AT)
    new_song = trending(page).get_by_role("link").first
    expect(new_song).to_have_accessible_name("Slow Harbor by Neon Pilgrims")
    story.assert_not_reloaded()

    # Its page shows the lyrics; like it, then play it from the big green button.
    new_song.click()
    expect(page.get_by_role("heading", level=1, name="Slow Harbor")).to_be_visible()
    expect(page.get_by_role("region", name="Lyrics")).to_contain_text("A lighthouse blinking")
    page.get_by_role("button", name="Save to Liked Songs").click()
    expect(page.get_by_role("button", name="Remove from Liked Songs").first).to_be_visible()
    page.get_by_role("button", name="Play Slow Harbor", exact=True).click()
    player = page.get_by_role("contentinfo", name="Now playing")
    expect(player.get_by_role("link", name="Slow Harbor")).to_be_visible()
    expect(page.get_by_role("link", name=re.compile("^Liked Songs"))).to_be_visible()

    # Report back, then grade: the two actions, and only them.
    assert story.report() == [
        ("like_track", {"track_id": SONG}),
        ("play_track", {"track_id": SONG}),
    ]
