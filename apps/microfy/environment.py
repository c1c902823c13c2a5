"""MicroFy's registration with the core: scenario events, baselines, evaluation tables.

Scenario events (SentinelBench format; every list may be `["*"]`):
- `preload_tracks {track_ids, playlist_ids, mood_ids, liked_track_ids?, followed_artist_ids?}`
  — the library when the task starts; liked ids count only for tracks it loads. Baselines are
  measured right after it applies.
- `new_track {track_id}` — a track drops into the trending feed, not liked and never played.
- `new_playlist {playlist_id}` — a catalog playlist appears (unknown ids change nothing).
- `make_track_unavailable {track_id}` — a track becomes unavailable now (apps.kit.retractions).

A track id delivered twice is the same track: the original appended a duplicate row and reset
its state; here it is left as it is (no duplicate, nothing the user did is lost).
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

from pydantic import Field

from apps.kit.arrivals import Delivery, arrival, event_types, preload
from apps.kit.counts import ShownCount
from apps.kit.environments import declare
from apps.kit.retractions import retraction, window
from apps.kit.state import with_changed
from apps.kit.streaming import read_at
from apps.kit.tables import KEY, Table, tables
from apps.microfy import screens
from apps.microfy import state as lib
from apps.microfy.catalog import artists, catalog_mood, catalog_playlist, catalog_track
from apps.microfy.state import ENVIRONMENT, Music, TrackState, empty_music, with_followed
from events.registry import counted
from events.schemas import Payload

# The original's names: eval_sql reads session_meta `baseline_<name>`.
BASELINES = counted(
    {
        "liked_count": lib.liked_count,
        "play_count": lib.play_count,
        "new_release_count": lib.new_release_count,
        "playlist_count": lib.playlist_count,
        "public_playlist_count": lib.public_playlist_count,
        "followed_artist_count": lib.followed_artist_count,
        "track_count": lib.track_count,
    }
)

deliver_tracks = Delivery("tracks", catalog_track, states="states", fresh=TrackState)
deliver_playlists = Delivery("playlists", catalog_playlist)


class LikedAndFollowed(Payload):
    """What the user already liked and followed when the task starts."""

    liked_track_ids: list[str] = Field([], description="tracks already liked (if loaded)")
    followed_artist_ids: list[str] = Field([], description="artists already followed")


def like_and_follow(music: Music, payload: Mapping[str, Any], at: float) -> Music:
    """Likes count only for tracks the preload loaded; follows only for known artists."""
    catalog = music.catalog
    for track_id in catalog.expand(ENVIRONMENT, "tracks", payload.get("liked_track_ids")):
        music = with_changed(music, "states", track_id, is_liked=True)
    known = catalog.index(artists)
    for artist_id in catalog.expand(ENVIRONMENT, "artists", payload.get("followed_artist_ids")):
        if artist_id in known and not music.is_followed(artist_id):
            music = with_followed(music, artist_id, True)
    return music


EVENT_TYPES = event_types(
    preload(
        "preload_tracks",
        {
            "track_ids": ("tracks", deliver_tracks),
            "playlist_ids": ("playlists", deliver_playlists),
            "mood_ids": ("moods", Delivery("moods", catalog_mood)),
        },
        required=("track_ids",),
        base=LikedAndFollowed,
        then=like_and_follow,
        refs={"liked_track_ids": "tracks"},
        environment=ENVIRONMENT,
        help="The library at the start; baselines are measured after it.",
    ),
    arrival(
        "new_track",
        "track_id",
        "tracks",
        deliver_tracks,
        help="A track drops into the trending feed.",
    ),
    retraction(
        "make_track_unavailable",
        "track_id",
        "tracks",
        "tracks",
        help="A track becomes unavailable (its rights pulled): greyed out where it is listed, "
        "gone from the shelves and search, it can no longer be played, saved or added.",
    ),
    arrival(
        "new_playlist",
        "playlist_id",
        "playlists",
        deliver_playlists,
        help="A catalog playlist appears in the library.",
    ),
)


# --- evaluation tables (the original's names and columns; playCount and artists are ours) -------


def user_playlist_data(playlist: lib.Playlist) -> str:
    """The original's JSON of a user-created playlist (the `data` column)."""
    return json.dumps(
        {
            "id": playlist.id,
            "name": playlist.name,
            "description": playlist.description,
            "trackIds": list(playlist.track_ids),
            "source": "user",
        }
    )


ID_AND_NAME = {"id TEXT": "id", "name TEXT": "name"}

materialize = tables(
    Table(
        "tracks",
        read_at(lambda music: music.tracks.values()),
        {
            "id TEXT": "id",
            "title TEXT": "title",
            "artistId TEXT": "artist_id",
            "artistName TEXT": "artist_name",
            "genre TEXT": "genre",
            "isNewRelease INTEGER": "is_new_release",
            "lyrics TEXT": "lyrics",
            # Everyone's plays at `now` (as the track page shows them), the user's included.
            "playCount INTEGER": lambda t: screens.plays_at(t.state, t.item, t.now),
            **window("arrived_at"),
        },
    ),
    Table.keyed(
        "track_states",
        "states",
        {
            "track_id TEXT": KEY,
            "isLiked INTEGER": "is_liked",
            "userPlayCount INTEGER": "user_play_count",
        },
    ),
    Table.items("playlists", {**ID_AND_NAME, "data TEXT": "data"}),
    Table.items(
        "user_created_playlists", {**ID_AND_NAME, "data TEXT": user_playlist_data}, "user_playlists"
    ),
    Table("followed_artists", lambda music, now: music.followed, {"artist_id TEXT": lambda a: a}),
    Table.items("moods", ID_AND_NAME),
    Table(
        "artists",
        read_at(screens.top_artists),
        {
            "id TEXT": "id",
            "name TEXT": "name",
            "monthlyListeners INTEGER": lambda a: screens.count_at(a.listeners, a.now),
            "followers INTEGER": lambda a: screens.follower_count(a.state, a.item, a.now),
        },
    ),
)


# The numbers shown in more than one place (apps.kit.counts): Liked Songs in the library and on
# its own page.
SHOWN_COUNTS = (
    ShownCount(
        "liked songs",
        lambda music, now: len(screens.liked_tracks(music)),
        ("Liked Songs [^•]*• {n} songs?",),  # "Playlist • 6 songs", "<owner> • 6 songs, 19:16"
    ),
)


MICROFY = declare(__name__, title="MicroFy", initial_state=empty_music)
