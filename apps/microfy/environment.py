"""MicroFy's registration with the core: scenario events, baselines, evaluation tables.

Scenario events (SentinelBench format; every list may be `["*"]`):
- `preload_tracks {track_ids, playlist_ids, mood_ids, liked_track_ids?, followed_artist_ids?}`
  — the library when the task starts; liked ids count only for tracks it loads. Baselines are
  measured right after it applies.
- `new_track {track_id}` — a track drops into the trending feed, not liked and never played.
- `new_playlist {playlist_id}` — a catalog playlist appears (unknown ids change nothing).

A track id delivered twice is the same track: the original appended a duplicate row and reset
its state; here it is left as it is (no duplicate, nothing the user did is lost).
"""

from __future__ import annotations

import json
import sqlite3
from collections.abc import Mapping
from dataclasses import replace
from types import MappingProxyType
from typing import Any

from pydantic import Field

from apps.kit.legacy_tables import Table
from apps.microfy import library
from apps.microfy import state as lib
from apps.microfy.actions import ACTIONS
from apps.microfy.bench import sample_pages
from apps.microfy.catalog import artists, catalog_mood, catalog_playlist, catalog_track, fresh_state
from apps.microfy.state import ENVIRONMENT, Music, with_playlists, with_tracks
from events.registry import Environment, EventType, LoggedEvent, Measure, timeless
from events.schemas import Payload

FALLBACK_SELF: Mapping[str, Any] = MappingProxyType({"id": "me", "name": "Me"})

# The original's names: eval_sql reads session_meta `baseline_<name>`.
BASELINES: Mapping[str, Measure] = MappingProxyType(
    {
        name: timeless(count)
        for name, count in {
            "liked_count": lib.liked_count,
            "play_count": lib.play_count,
            "new_release_count": lib.new_release_count,
            "playlist_count": lib.playlist_count,
            "public_playlist_count": lib.public_playlist_count,
            "followed_artist_count": lib.followed_artist_count,
            "track_count": lib.track_count,
        }.items()
    }
)


def empty_music(catalog: Any) -> Music:
    me = catalog.self_user or FALLBACK_SELF
    return Music(catalog=catalog, self_id=str(me.get("id", "")), self_name=str(me.get("name", "")))


def deliver_tracks(music: Music, track_ids: list[str], *, at: float, preloaded: bool) -> Music:
    arrivals = []
    for track_id in dict.fromkeys(track_ids):  # de-duplicate, keep order
        if music.has(track_id):
            continue
        track = catalog_track(music.catalog, track_id, arrived_at=at, preloaded=preloaded)
        if track is not None:
            arrivals.append((track, fresh_state()))
    return with_tracks(music, arrivals) if arrivals else music


def reduce_preload_tracks(music: Music, event: LoggedEvent) -> Music:
    payload, catalog = event.payload, music.catalog
    music = deliver_tracks(
        music,
        catalog.expand(ENVIRONMENT, "tracks", payload.get("track_ids")),
        at=event.at,
        preloaded=True,
    )
    playlists = [
        catalog_playlist(catalog, p)
        for p in catalog.expand(ENVIRONMENT, "playlists", payload.get("playlist_ids"))
        if p not in music.playlists
    ]
    music = with_playlists(music, [p for p in playlists if p is not None])
    moods = {**music.moods}
    for mood_id in catalog.expand(ENVIRONMENT, "moods", payload.get("mood_ids")):
        mood = catalog_mood(catalog, mood_id)
        if mood is not None:
            moods[mood_id] = mood
    music = replace(music, moods=MappingProxyType(moods))
    for track_id in catalog.expand(ENVIRONMENT, "tracks", payload.get("liked_track_ids")):
        music = lib.with_track_state(music, track_id, is_liked=True)
    known = catalog.index(artists)
    for artist_id in catalog.expand(ENVIRONMENT, "artists", payload.get("followed_artist_ids")):
        if artist_id in known and not music.is_followed(artist_id):
            music = lib.with_followed(music, artist_id, True)
    return music


def reduce_new_track(music: Music, event: LoggedEvent) -> Music:
    return deliver_tracks(music, [event.payload["track_id"]], at=event.at, preloaded=False)


def reduce_new_playlist(music: Music, event: LoggedEvent) -> Music:
    playlist_id = event.payload["playlist_id"]
    if playlist_id in music.playlists:
        return music
    playlist = catalog_playlist(music.catalog, playlist_id)
    return with_playlists(music, [playlist]) if playlist is not None else music


class PreloadTracks(Payload):
    track_ids: list[str] = Field(description='catalog track ids; ["*"] = every track')
    playlist_ids: list[str] = Field([], description='catalog playlist ids; ["*"] = every one')
    mood_ids: list[str] = Field([], description='catalog mood ids; ["*"] = every mood')
    liked_track_ids: list[str] = Field([], description="tracks already liked (if loaded)")
    followed_artist_ids: list[str] = Field([], description="artists already followed")


class NewTrack(Payload):
    track_id: str = Field(description="catalog track id")


class NewPlaylist(Payload):
    playlist_id: str = Field(description="catalog playlist id")


EVENT_TYPES = MappingProxyType(
    {
        "preload_tracks": EventType(
            schema=PreloadTracks,
            reduce=reduce_preload_tracks,
            help="The library at the start; baselines are measured after it.",
            catalog_refs={
                "track_ids": "tracks",
                "playlist_ids": "playlists",
                "mood_ids": "moods",
                "liked_track_ids": "tracks",
            },
            preload=True,
        ),
        "new_track": EventType(
            schema=NewTrack,
            reduce=reduce_new_track,
            help="A track drops into the trending feed.",
            catalog_refs={"track_id": "tracks"},
        ),
        "new_playlist": EventType(
            schema=NewPlaylist,
            reduce=reduce_new_playlist,
            help="A catalog playlist appears in the library.",
            catalog_refs={"playlist_id": "playlists"},
        ),
    }
)


# --- evaluation tables (the original's names and columns; playCount and artists are ours) -------

TRACKS = Table(
    "tracks",
    (
        "id TEXT",
        "title TEXT",
        "artistId TEXT",
        "artistName TEXT",
        "genre TEXT",
        "isNewRelease INTEGER",
        "lyrics TEXT",
        "playCount INTEGER",
    ),
)
TRACK_STATES = Table("track_states", ("track_id TEXT", "isLiked INTEGER", "userPlayCount INTEGER"))
PLAYLISTS = Table("playlists", ("id TEXT", "name TEXT", "data TEXT"))
USER_PLAYLISTS = Table("user_created_playlists", ("id TEXT", "name TEXT", "data TEXT"))
FOLLOWED = Table("followed_artists", ("artist_id TEXT",))
MOODS = Table("moods", ("id TEXT", "name TEXT"))
ARTISTS = Table(
    "artists", ("id TEXT", "name TEXT", "monthlyListeners INTEGER", "followers INTEGER")
)


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


def materialize(music: Music, now: float, conn: sqlite3.Connection) -> None:
    """The original's six tables as of `now`, plus the drifting counts the pages show."""
    TRACKS.write(
        conn,
        (
            (
                t.id,
                t.title,
                t.artist_id,
                t.artist_name,
                t.genre,
                t.is_new_release,
                t.lyrics,
                library.count_at(t.plays, now) + music.states[t.id].user_play_count,
            )
            for t in music.tracks.values()
        ),
    )
    TRACK_STATES.write(
        conn,
        ((i, s.is_liked, s.user_play_count) for i, s in music.states.items()),
    )
    PLAYLISTS.write(conn, ((p.id, p.name, p.data) for p in music.playlists.values()))
    USER_PLAYLISTS.write(
        conn, ((p.id, p.name, user_playlist_data(p)) for p in music.user_playlists.values())
    )
    FOLLOWED.write(conn, ((a,) for a in music.followed))
    MOODS.write(conn, ((m.id, m.name) for m in music.moods.values()))
    ARTISTS.write(
        conn,
        (
            (
                a.id,
                a.name,
                library.count_at(a.listeners, now),
                library.follower_count(music, a, now),
            )
            for a in library.top_artists(music)
        ),
    )


MICROFY = Environment(
    name=ENVIRONMENT,
    title="MicroFy",
    initial_state=empty_music,
    event_types=EVENT_TYPES,
    actions=ACTIONS,
    baselines=BASELINES,
    materialize=materialize,
    urlconf="apps.microfy.urls",
    sample_pages=sample_pages,
)
