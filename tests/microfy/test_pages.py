"""MicroFy pages over runs of our scenarios (virtual clock): what each screen shows, what is
hidden until its event fires, the forms that act, and the values that move with the clock."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from django.conf import settings
from django.test import Client

from apps.kit.live import render_update
from apps.scenarios.format import load_scenario_file
from events import lifecycle
from events.commands import current_state
from events.evaluation import grading_snapshot
from events.models import ClockMode, Event, EventKind
from events.sandbox import run_eval_sql

pytestmark = pytest.mark.django_db

LIGHTHOUSE_AT = 276.9  # track-057, "Slow Harbor" by Neon Pilgrims, mentions a lighthouse


def start(name: str):
    path = Path(settings.SENTINEL_SCENARIO_DIR) / "microfy" / f"{name}.json"
    return lifecycle.create_run(
        load_scenario_file(path).to_run_spec(), clock_mode=ClockMode.VIRTUAL
    )


@pytest.fixture
def run():
    return start("lyric-lighthouse-absolute-active")


@pytest.fixture
def get(run):
    client = Client()

    def get(path: str = "", status: int = 200) -> str:
        response = client.get(f"/r/{run.token}/microfy/{path}")
        assert response.status_code == status, response.content[:300]
        return response.content.decode()

    get.client = client
    return get


def post(get, run, path: str, data: dict | None = None) -> None:
    response = get.client.post(f"/r/{run.token}/microfy/{path}", data or {})
    assert response.status_code == 302, response.content[:300]


def actions(run) -> list[str]:
    return list(Event.objects.filter(run=run, kind=EventKind.ACTION).values_list("type", flat=True))


def test_a_track_is_nowhere_until_its_event_fires(run, get):
    assert "Slow Harbor" not in get() and "Slow Harbor" not in get("search?q=slow+harbor")
    get("track/track-057", status=404)
    lifecycle.advance(run, LIGHTHOUSE_AT)
    home = get()
    trending = home[home.index('id="trending"') :]
    assert trending.index("Slow Harbor") < trending.index("Restless Freeways")  # newest first
    assert "Slow Harbor" in get("search?q=slow+harbor")
    assert "A lighthouse blinking out at sea" in get("track/track-057")  # lyrics on its page


def test_every_screen_renders_and_unknown_items_are_404(get):
    home = get()
    for text in ("Trending Songs", "New Releases", "Top Artists", "Pick a Mood", "Your Library"):
        assert text in home
    assert "Velvet Harbor" in get("artist/artist-001")
    assert "monthly listeners" in get("artist/artist-001")
    assert "Liked Songs" in get("playlist/liked")
    assert "Indie Discoveries" in get("playlist/playlist-009")
    assert 'aria-current="true"' in get("?mood=mood-002")
    assert "Browse all" in get("search")
    get("track/track-999", status=404)
    get("artist/artist-041", status=404)  # Glass Satellite: no track of theirs in the session
    get("playlist/playlist-020", status=404)  # not loaded
    get("?mood=mood-006", status=404)


def test_like_play_follow_and_playlists_through_the_forms(run, get):
    post(get, run, "tracks/track-003/like_track", {"back": "track/track-003"})
    post(get, run, "tracks/track-003/play_track", {"back": "track/track-003"})
    post(get, run, "artists/artist-003/follow_artist", {"back": "artist/artist-003"})
    post(get, run, "playlists", {"name": "Night Drive", "description": "for later"})
    post(get, run, "tracks/track-003/add_to_playlist", {"playlist_id": "user-playlist-1"})
    music = current_state(run)
    assert music.is_liked("track-003") and music.states["track-003"].user_play_count == 1
    assert music.followed[-1] == "artist-003"
    assert music.user_playlists["user-playlist-1"].track_ids == ("track-003",)
    assert actions(run) == [
        "like_track",
        "play_track",
        "follow_artist",
        "create_playlist",
        "add_to_playlist",
    ]
    page = get("playlist/user-playlist-1")
    assert "Night Drive" in page and "1 song" in page
    assert 'aria-label="Now playing"' in get() and "Following" in get("artist/artist-003")


def test_refused_actions_name_the_reason(run, get):
    response = get.client.post(f"/r/{run.token}/microfy/tracks/track-057/like_track", {})
    assert response.status_code == 404 and b"track-057" in response.content
    response = get.client.post(f"/r/{run.token}/microfy/playlists", {"name": "  "})
    assert response.status_code == 400 and b"name" in response.content


def test_the_player_position_follows_the_simulated_clock(run, get):
    lifecycle.advance(run, 20.0)
    post(get, run, "tracks/track-001/play_track")
    assert "0:00" in get()
    lifecycle.advance(run, 33.0)  # 13 s in: shown in 5-second steps
    assert re.search(r'<span class="time">0:10</span>', get())


def test_a_track_made_unavailable_while_playing_leaves_the_open_pages_player_idle():
    run = start("pulled-single-ephemeral-active")  # Secret Stations: 327.8 s, gone at 417.8 s
    client = Client()
    page = f"/r/{run.token}/microfy/track/track-090"
    lifecycle.advance(run, 327.8)
    client.post(f"/r/{run.token}/microfy/tracks/track-090/play_track", {"back": "track/track-090"})

    def player() -> str:
        return dict(render_update(run, page).regions)["player"]

    assert "Secret Stations" in player() and 'aria-label="Pause"' in player()
    lifecycle.advance(run, 417.8)
    assert "Secret Stations" not in player() and "Pick something to play" in player()
    response = client.post(f"/r/{run.token}/microfy/tracks/track-090/play_track", {})
    assert response.status_code == 404 and b"track-090" in response.content


def test_an_artists_listeners_drift_and_the_page_agrees_with_the_tables(run, get):
    def listeners() -> int:
        text = re.search(r"([\d,]+) monthly listeners", get("artist/artist-001")).group(1)
        return int(text.replace(",", ""))

    first = listeners()
    lifecycle.advance(run, 300.0)
    later = listeners()
    assert later > first
    outcome = run_eval_sql(
        "SELECT monthlyListeners FROM artists WHERE id = 'artist-001'", grading_snapshot(run).write
    )
    assert outcome.value == later


def due(html: str) -> float | None:
    """When the page said it next changes on the simulated clock (the live client's data-due)."""
    found = re.search(r'data-due="([^"]*)"', html)
    return float(found.group(1)) if found and found.group(1) else None


def test_pages_showing_moving_values_say_when_they_next_change(run, get):
    # Listeners tick over within seconds, but an open page is pushed them with the clock's
    # minute at the soonest (a reload shows them at once); the player moves in 5-second steps.
    assert due(get("artist/artist-001")) == 60.0
    post(get, run, "tracks/track-001/play_track")
    assert due(get("playlist/liked")) == 5.0
    lifecycle.advance(run, 7.0)
    assert due(get("playlist/liked")) == 10.0
