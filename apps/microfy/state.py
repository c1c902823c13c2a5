"""The music library as immutable values, and the questions pages and baselines ask of it.

`Music` is what the reducers build and what every page, baseline and evaluation reads. It is
never mutated: a reducer returns a new `Music`. Tracks are kept in arrival order (the trending
row shows the newest first); a track's all-time plays and an artist's listeners move with the
clock as `Waypoints` series, read at the operation's one `now`.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass, replace
from types import MappingProxyType
from typing import ClassVar

from apps.kit.records import flag, from_catalog, text, text_or, texts
from apps.kit.state import SelfUserState
from apps.kit.streaming import counting, no_items, whole
from apps.kit.waypoints import Waypoints

ENVIRONMENT = "microfy"
LIKED = "liked"  # the Liked Songs collection's id in URLs
USER_PLAYLIST_PREFIX = "user-playlist"  # the original's ids for playlists the user creates
UNKNOWN_ARTIST = "Unknown Artist"


@dataclass(frozen=True)
class Track:
    """One song as the catalog describes it, stamped with when it reached the session."""

    id: str
    title: str = from_catalog(text("title"))
    artist_id: str = from_catalog(text("artistId"))
    artist_name: str = from_catalog(text_or("artistName", UNKNOWN_ARTIST))
    album: str = from_catalog(text("albumName"))
    duration_s: int = from_catalog(lambda r: whole(r.get("durationSeconds"), 180))
    description: str = from_catalog(text("description"))
    genre: str = from_catalog(text("genre"))
    lyrics: str = from_catalog(text("lyrics"))
    is_new_release: bool = from_catalog(flag("isNewRelease"))
    plays: Waypoints  # all-time plays by everyone (drifts upward over the session)
    arrived_at: float = 0.0
    preloaded: bool = True
    gone_at: float | None = None  # made unavailable then (apps.kit.retractions)

    @property
    def duration(self) -> str:
        return clock_text(self.duration_s)


@dataclass(frozen=True)
class TrackState:
    """What this user did to a track (the original's track_states row)."""

    is_liked: bool = False
    user_play_count: int = 0


@dataclass(frozen=True)
class Artist:
    id: str
    name: str
    genre: str
    bio: str
    listeners: Waypoints  # monthly listeners (drift)
    followers: Waypoints  # followers by everyone else (drift; the user's follow adds one)


@dataclass(frozen=True)
class Playlist:
    """A catalog playlist, or one the user created (`owner_id` is then the self user)."""

    id: str
    name: str = from_catalog(text("name"))
    description: str = from_catalog(text("description"))
    owner_id: str = from_catalog(text("ownerId"))
    owner_name: str = from_catalog(text("ownerName"))
    track_ids: tuple[str, ...] = from_catalog(texts("trackIds"))
    follower_count: int = from_catalog(lambda r: whole(r.get("followerCount")), default=0)
    is_public: bool = from_catalog(lambda r: bool(r.get("isPublic", True)), default=True)
    # the catalog record as JSON: the `playlists.data` column
    data: str = from_catalog(lambda r: json.dumps(dict(r)), default="{}")

    @property
    def cover_seed(self) -> str:
        return self.name


@dataclass(frozen=True)
class Mood:
    id: str
    name: str = from_catalog(text("name"))
    description: str = from_catalog(text("description"))
    colour: str = from_catalog(text_or("coverColor", "#535353"))


@dataclass(frozen=True)
class NowPlaying:
    track_id: str
    started_at: float  # simulated seconds: the position is `now - started_at`


@dataclass(frozen=True)
class Music(SelfUserState):
    FALLBACK: ClassVar[Mapping[str, str]] = MappingProxyType({"id": "me", "name": "Me"})
    tracks: Mapping[str, Track] = no_items()  # arrival order
    states: Mapping[str, TrackState] = no_items()
    playlists: Mapping[str, Playlist] = no_items()  # catalog playlists loaded, arrival order
    user_playlists: Mapping[str, Playlist] = no_items()  # creation order
    followed: tuple[str, ...] = ()  # artist ids, in the order they were followed
    moods: Mapping[str, Mood] = no_items()
    now_playing: NowPlaying | None = None

    def is_liked(self, track_id: str) -> bool:
        state = self.states.get(track_id)
        return bool(state and state.is_liked)

    def is_followed(self, artist_id: str) -> bool:
        return artist_id in self.followed

    def playlist(self, playlist_id: str) -> Playlist | None:
        return self.playlists.get(playlist_id) or self.user_playlists.get(playlist_id)

    def own_playlists(self) -> tuple[Playlist, ...]:
        """The playlists the user can add to: the catalog's that the user owns (the library
        says "Playlist • you"), then those the user created — Spotify's "Add to playlist"."""
        owned = (p for p in self.playlists.values() if p.owner_id == self.self_id)
        return (*owned, *self.user_playlists.values())

    def owns_playlist(self, playlist_id: str) -> bool:
        return any(p.id == playlist_id for p in self.own_playlists())


empty_music = Music.of  # catalog → the empty library, its self user in place


def clock_text(seconds: float) -> str:
    """`203` → `"3:23"` (a player's time)."""
    whole = max(0, int(seconds))
    return f"{whole // 60}:{whole % 60:02d}"


def with_followed(music: Music, artist_id: str, followed: bool) -> Music:
    rest = tuple(a for a in music.followed if a != artist_id)
    return replace(music, followed=(*rest, artist_id) if followed else rest)


# --- counts (baselines and badges) ----------------------------------------------------------------

liked_count = counting("states", "is_liked")
new_release_count = counting("tracks", "is_new_release")
playlist_count = counting("user_playlists")  # the user created (the original's `playlist_count`)
public_playlist_count = counting("playlists")  # catalog playlists loaded in the session
followed_artist_count = counting("followed")
track_count = counting("tracks")


def play_count(music: Music) -> int:
    return sum(s.user_play_count for s in music.states.values())
