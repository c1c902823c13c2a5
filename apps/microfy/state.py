"""The music library as immutable values, and the questions pages and baselines ask of it.

`Music` is what the reducers build and what every page, baseline and evaluation reads. It is
never mutated: a reducer returns a new `Music`. Tracks are kept in arrival order (the trending
row shows the newest first); a track's all-time plays and an artist's listeners move with the
clock as `Waypoints` series, read at the operation's one `now`.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import Any

from apps.kit.waypoints import Waypoints

ENVIRONMENT = "microfy"
LIKED = "liked"  # the Liked Songs collection's id in URLs
USER_PLAYLIST_PREFIX = "user-playlist-"  # the original's ids for playlists the user creates

EMPTY: Mapping = MappingProxyType({})


@dataclass(frozen=True)
class Track:
    """One song as the catalog describes it, stamped with when it reached the session."""

    id: str
    title: str
    artist_id: str
    artist_name: str
    album: str
    duration_s: int
    description: str
    genre: str
    lyrics: str
    is_new_release: bool
    plays: Waypoints  # all-time plays by everyone (drifts upward over the session)
    arrived_at: float = 0.0
    preloaded: bool = True

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
    name: str
    description: str
    owner_id: str
    owner_name: str
    track_ids: tuple[str, ...]
    follower_count: int = 0
    is_public: bool = True
    user_created: bool = False
    data: str = "{}"  # the catalog record as JSON: the `playlists.data` column

    @property
    def cover_seed(self) -> str:
        return self.name


@dataclass(frozen=True)
class Mood:
    id: str
    name: str
    description: str
    colour: str


@dataclass(frozen=True)
class NowPlaying:
    track_id: str
    started_at: float  # simulated seconds: the position is `now - started_at`


@dataclass(frozen=True)
class Music:
    catalog: Any
    self_id: str
    self_name: str
    tracks: Mapping[str, Track] = field(default_factory=lambda: EMPTY)  # arrival order
    states: Mapping[str, TrackState] = field(default_factory=lambda: EMPTY)
    playlists: Mapping[str, Playlist] = field(
        default_factory=lambda: EMPTY
    )  # catalog playlists loaded, arrival order
    user_playlists: Mapping[str, Playlist] = field(default_factory=lambda: EMPTY)  # creation order
    followed: tuple[str, ...] = ()  # artist ids, in the order they were followed
    moods: Mapping[str, Mood] = field(default_factory=lambda: EMPTY)
    now_playing: NowPlaying | None = None

    def has(self, track_id: str) -> bool:
        return track_id in self.tracks

    def is_liked(self, track_id: str) -> bool:
        state = self.states.get(track_id)
        return bool(state and state.is_liked)

    def is_followed(self, artist_id: str) -> bool:
        return artist_id in self.followed

    def playlist(self, playlist_id: str) -> Playlist | None:
        return self.playlists.get(playlist_id) or self.user_playlists.get(playlist_id)


def clock_text(seconds: float) -> str:
    """`203` → `"3:23"` (a player's time)."""
    whole = max(0, int(seconds))
    return f"{whole // 60}:{whole % 60:02d}"


def _frozen(mapping: Mapping) -> Mapping:
    return MappingProxyType(dict(mapping))


def with_tracks(music: Music, arrivals: Iterable[tuple[Track, TrackState]]) -> Music:
    tracks, states = dict(music.tracks), dict(music.states)
    for track, state in arrivals:
        tracks[track.id] = track
        states[track.id] = state
    return replace(music, tracks=_frozen(tracks), states=_frozen(states))


def with_track_state(music: Music, track_id: str, **changes: Any) -> Music:
    """`music` with the track's state changed; an unknown id changes nothing (replay-safe)."""
    if track_id not in music.states:
        return music
    states = dict(music.states)
    states[track_id] = replace(states[track_id], **changes)
    return replace(music, states=_frozen(states))


def with_playlists(music: Music, playlists: Iterable[Playlist]) -> Music:
    loaded = dict(music.playlists)
    for playlist in playlists:
        loaded[playlist.id] = playlist
    return replace(music, playlists=_frozen(loaded))


def with_user_playlist(music: Music, playlist: Playlist) -> Music:
    return replace(music, user_playlists=_frozen({**music.user_playlists, playlist.id: playlist}))


def with_followed(music: Music, artist_id: str, followed: bool) -> Music:
    rest = tuple(a for a in music.followed if a != artist_id)
    return replace(music, followed=(*rest, artist_id) if followed else rest)


def next_user_playlist_id(music: Music) -> str:
    """The original's numbering: `user-playlist-<count + 1>`."""
    return f"{USER_PLAYLIST_PREFIX}{len(music.user_playlists) + 1}"


# --- counts (baselines and badges) ----------------------------------------------------------------


def liked_count(music: Music) -> int:
    return sum(1 for s in music.states.values() if s.is_liked)


def play_count(music: Music) -> int:
    return sum(s.user_play_count for s in music.states.values())


def new_release_count(music: Music) -> int:
    return sum(1 for t in music.tracks.values() if t.is_new_release)


def playlist_count(music: Music) -> int:
    """Playlists the user created (the original's `playlist_count`)."""
    return len(music.user_playlists)


def public_playlist_count(music: Music) -> int:
    """Catalog playlists loaded in the session."""
    return len(music.playlists)


def followed_artist_count(music: Music) -> int:
    return len(music.followed)


def track_count(music: Music) -> int:
    return len(music.tracks)
