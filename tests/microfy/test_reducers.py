"""MicroFy's reducers, actions, baselines and evaluation tables on our catalog (no database)."""

from __future__ import annotations

import json
import sqlite3

import pytest

from apps.microfy import screens
from apps.microfy.environment import MICROFY, materialize
from events.catalog import load_catalog
from events.registry import ActionRejected
from tests.microfy.cast import CAST, FIRST_TEN, SLOW_HARBOR, arrive

act, preloaded = CAST.act, CAST.preloaded


def tables(music, now: float = 0.0) -> sqlite3.Connection:
    conn = sqlite3.connect(":memory:")
    materialize(music, now, conn)
    return conn


def test_preload_loads_tracks_playlists_moods_likes_and_follows():
    music = preloaded(
        track_ids=[*FIRST_TEN, "track-999"],
        playlist_ids=["playlist-001", "playlist-404"],
        mood_ids=["*"],
        liked_track_ids=["track-002", "track-050"],  # 050 is not loaded: not liked
        followed_artist_ids=["artist-004", "artist-nope"],
    )
    assert list(music.tracks) == FIRST_TEN
    assert list(music.playlists) == ["playlist-001"] and len(music.moods) == 6
    assert [i for i, s in music.states.items() if s.is_liked] == ["track-002"]
    assert music.followed == ("artist-004",)


def test_every_wildcard_list_means_the_whole_table():
    music = preloaded(track_ids=["*"], playlist_ids=["*"], mood_ids=["*"])
    catalog = load_catalog()
    whole = (len(catalog.table("microfy", "tracks")), len(catalog.table("microfy", "playlists")))
    assert (len(music.tracks), len(music.playlists)) == whole
    assert whole[0] >= 100  # the catalog, not an empty table


def test_a_new_track_arrives_fresh_first_in_trending_and_a_repeat_changes_nothing():
    music = act(arrive(preloaded(), "track-057", at=30.0), "like_track", {"track_id": "track-057"})
    assert screens.trending(music)[0].id == "track-057"
    assert screens.new_releases(music)[0].id == "track-057"
    again = arrive(music, "track-057", at=60.0)
    assert again is music  # no duplicate row, the like is kept


def test_new_playlist_appears_in_the_sidebar_and_unknown_ids_are_ignored():
    music = preloaded(playlist_ids=["playlist-001"])
    music = CAST.arrive(music, "new_playlist", {"playlist_id": "playlist-015"})
    music = CAST.arrive(music, "new_playlist", {"playlist_id": "playlist-999"})
    assert [e.id for e in screens.library_entries(music)] == ["playlist-001", "playlist-015"]


def test_play_counts_every_press_and_starts_the_player():
    music = act(
        act(preloaded(), "play_track", {"track_id": "track-003"}, at=40.0),
        "play_track",
        {"track_id": "track-003"},
        at=50.0,
    )
    assert music.states["track-003"].user_play_count == 2
    player, changes = screens.player(music, 57.0)
    assert (player.track.id, player.position_s, changes) == ("track-003", 5.0, 60.0)
    ended, never = screens.player(music, 50.0 + music.tracks["track-003"].duration_s)
    assert ended.playing is False and never is None


def test_a_track_made_unavailable_while_playing_stops_and_cannot_be_played_again():
    music = act(arrive(preloaded(), SLOW_HARBOR, at=30.0), "play_track", {"track_id": SLOW_HARBOR})
    playing, _ = screens.player(music, 60.0)
    assert playing.track.id == SLOW_HARBOR and playing.playing
    music = CAST.arrive(music, "make_track_unavailable", {"track_id": SLOW_HARBOR}, at=60.0)
    assert screens.player(music, 60.0) == (None, None)  # nothing playing: no queue to move on to
    with pytest.raises(ActionRejected, match="no track"):
        act(music, "play_track", {"track_id": SLOW_HARBOR}, at=70.0)
    # Another song plays on when one it is not goes.
    music = act(music, "play_track", {"track_id": "track-003"}, at=80.0)
    music = CAST.arrive(music, "make_track_unavailable", {"track_id": "track-004"}, at=90.0)
    assert screens.player(music, 90.0)[0].track.id == "track-003"


def test_like_and_unlike_are_explicit_and_follow_needs_an_artist_in_the_session():
    music = preloaded()
    music = act(
        act(music, "like_track", {"track_id": "track-001"}), "like_track", {"track_id": "track-001"}
    )
    assert music.is_liked("track-001")
    assert not act(music, "unlike_track", {"track_id": "track-001"}).is_liked("track-001")
    assert act(music, "follow_artist", {"artist_id": "artist-002"}).followed == ("artist-002",)
    with pytest.raises(ActionRejected, match="artist-041"):
        act(music, "follow_artist", {"artist_id": "artist-041"})  # no track of theirs here
    with pytest.raises(ActionRejected, match="track-057"):
        act(music, "like_track", {"track_id": "track-057"})  # not arrived yet


def test_playlists_of_your_own_take_numbered_ids_and_only_they_can_be_added_to():
    music = act(
        preloaded(playlist_ids=["playlist-001", "playlist-020"]),
        "create_playlist",
        {"name": "  Night Drive ", "description": None},
    )
    assert list(music.user_playlists) == ["user-playlist-1"]
    assert music.user_playlists["user-playlist-1"].name == "Night Drive"
    add = {"playlist_id": "user-playlist-1", "track_id": "track-004"}
    music = act(act(music, "add_to_playlist", add), "add_to_playlist", add)
    assert music.user_playlists["user-playlist-1"].track_ids == ("track-004",)
    with pytest.raises(ActionRejected, match="only playlists you own"):
        act(music, "add_to_playlist", {**add, "playlist_id": "playlist-020"})  # someone else's
    with pytest.raises(ActionRejected, match=r"^name"):
        act(music, "create_playlist", {"name": "   "})


def test_baselines_are_the_originals_counts():
    music = preloaded(
        playlist_ids=["playlist-001", "playlist-002"],
        liked_track_ids=["track-001"],
        followed_artist_ids=["artist-003"],
    )
    assert dict(MICROFY.measure_baselines(music, 0.0)) == {
        "liked_count": 1,
        "play_count": 0,
        "new_release_count": 1,  # track-009
        "playlist_count": 0,
        "public_playlist_count": 2,
        "followed_artist_count": 1,
        "track_count": 10,
    }


def test_the_evaluation_tables_have_the_originals_names_and_columns():
    music = act(
        preloaded(playlist_ids=["playlist-001"], mood_ids=["mood-001"]),
        "like_track",
        {"track_id": "track-009"},
    )
    conn = tables(music)
    liked = conn.execute(
        "SELECT t.id FROM track_states ts JOIN tracks t ON t.id = ts.track_id "
        "WHERE LOWER(t.lyrics) LIKE '%copper%' AND ts.isLiked = 1"
    ).fetchall()
    assert liked == [("track-009",)]
    assert conn.execute("SELECT id, name FROM moods").fetchall() == [("mood-001", "Energetic")]
    assert '"trackIds"' in conn.execute("SELECT data FROM playlists").fetchone()[0]
    assert conn.execute("SELECT COUNT(*) FROM user_created_playlists").fetchone() == (0,)
    assert conn.execute("SELECT COUNT(*) FROM followed_artists").fetchone() == (0,)


def test_drifting_counts_grow_and_page_and_tables_agree_at_the_same_instant():
    music = act(preloaded(), "play_track", {"track_id": "track-001"}, at=5.0)
    track, artist = music.tracks["track-001"], screens.top_artists(music)[-1]
    at_start, later = screens.count_at(track.plays, 0.0), screens.count_at(track.plays, 600.0)
    assert later > at_start
    assert screens.count_at(track.plays, 720.0) == screens.count_at(track.plays, 9999.0)
    row = (
        tables(music, 600.0)
        .execute("SELECT playCount FROM tracks WHERE id = 'track-001'")
        .fetchone()
    )
    assert row == (later + 1,)  # everyone's plays plus the user's
    shown = screens.count_at(artist.listeners, 300.0)
    change = artist.listeners.next_change(300.0, step=1)
    assert screens.count_at(artist.listeners, change) != shown
    assert screens.count_at(artist.listeners, (300.0 + change) / 2) == shown


def test_an_empty_catalog_state_is_safe():
    music = CAST.fresh()
    assert screens.trending(music) == () and screens.player(music, 0.0) == (None, None)


def test_the_track_page_offers_every_playlist_you_own_and_adding_to_one_shows_in_its_data():
    """Regression: "Add to playlist" offered only "Create a playlist first" beside the user's
    four playlists in the library (they came from the catalog, owned by the user)."""
    music = preloaded(playlist_ids=["playlist-001", "playlist-020"])
    assert [p.id for p in music.own_playlists()] == ["playlist-001"]  # not playlist-020
    music = act(music, "add_to_playlist", {"playlist_id": "playlist-001", "track_id": "track-004"})
    playlist = music.playlists["playlist-001"]
    assert playlist.track_ids[-1] == "track-004"
    assert json.loads(playlist.data)["trackIds"][-1] == "track-004"
