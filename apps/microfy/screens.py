"""What MicroFy's screens show, as pure functions of the library (memoised per state).

Only what has reached the session is shown anywhere: a track before its `new_track` event, a
playlist before its `new_playlist`, an artist with no track here yet (and not followed) are
absent from every row, count and search, and a 404 at their URL.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from apps.kit.derived import per_state
from apps.kit.retractions import present, still_there
from apps.kit.streaming import shown_count
from apps.kit.waypoints import Waypoints
from apps.microfy.catalog import artists, tracks_by_artist
from apps.microfy.state import LIKED, Artist, Music, Playlist, Track

HOME_ARTISTS = 10
POPULAR = 10
PLAYER_STEP_S = 5.0  # the player's position is shown, and re-rendered, every 5 simulated seconds


def count_at(series: Waypoints, now: float) -> int:
    """A drifting count as shown (a whole number) at `now`."""
    return shown_count(series.value_at(now))


def plays_at(music: Music, track: Track, now: float) -> int:
    """Everyone's plays at `now`, the user's own included (the track page's number)."""
    return count_at(track.plays, now) + music.states[track.id].user_play_count


def follower_count(music: Music, artist: Artist, now: float) -> int:
    """Everyone else's followers at `now`, plus the user once they follow."""
    return count_at(artist.followers, now) + (1 if music.is_followed(artist.id) else 0)


@per_state()
def trending(music: Music) -> tuple[Track, ...]:
    """Every track still available, newest arrival first (the original prepends each new track
    to the row). An unavailable one leaves the shelves and search, as on Spotify; the lists a
    person made (a playlist, Liked Songs) and an artist's keep it, greyed out."""
    available = present(music.tracks.values())
    arrived = [t for t in available if not t.preloaded]
    preloaded = [t for t in available if t.preloaded]
    arrived.sort(key=lambda t: t.arrived_at, reverse=True)
    return (*arrived, *preloaded)


@per_state()
def new_releases(music: Music) -> tuple[Track, ...]:
    """Tracks that dropped during the session (newest first), then catalog new releases."""
    return tuple(t for t in trending(music) if not t.preloaded or t.is_new_release)


@per_state()
def present_artist_ids(music: Music) -> frozenset[str]:
    return frozenset(t.artist_id for t in music.tracks.values()) | frozenset(music.followed)


def visible_artist(music: Music, artist_id: str) -> Artist | None:
    if artist_id not in present_artist_ids(music):
        return None
    return music.catalog.index(artists).get(artist_id)


@per_state()
def top_artists(music: Music) -> tuple[Artist, ...]:
    """Artists in the session in trending order (an artist new to the feed comes first)."""
    known = music.catalog.index(artists)
    seen: dict[str, Artist] = {}
    for track in trending(music):
        if track.artist_id not in seen and track.artist_id in known:
            seen[track.artist_id] = known[track.artist_id]
    return tuple(seen.values())


@per_state()
def artist_tracks(music: Music, artist_id: str) -> tuple[Track, ...]:
    ids = music.catalog.index(tracks_by_artist).get(artist_id, ())
    return tuple(music.tracks[t] for t in ids if t in music.tracks)


@per_state()
def liked_tracks(music: Music) -> tuple[Track, ...]:
    return tuple(t for t in music.tracks.values() if music.is_liked(t.id))


@per_state()
def playlist_tracks(music: Music, playlist_id: str) -> tuple[Track, ...]:
    if playlist_id == LIKED:
        return liked_tracks(music)
    playlist = music.playlist(playlist_id)
    if playlist is None:
        return ()
    return tuple(music.tracks[t] for t in playlist.track_ids if t in music.tracks)


@dataclass(frozen=True)
class LibraryEntry:
    """One row of the "Your Library" sidebar."""

    id: str
    name: str
    subtitle: str
    cover_seed: str
    liked: bool = False


@per_state()
def library_entries(music: Music) -> tuple[LibraryEntry, ...]:
    """Liked Songs (once something is liked), the catalog playlists in the session, then the
    user's own. The original listed only catalog playlists the user owned, so playlists that
    "appear in the sidebar" (its own scenario's wording) never did; every loaded one is listed."""
    entries = []
    liked = len(liked_tracks(music))
    if liked:
        entries.append(LibraryEntry(LIKED, "Liked Songs", f"Playlist • {liked} songs", "", True))
    for playlist in (*music.playlists.values(), *music.user_playlists.values()):
        owner = "you" if playlist.owner_id == music.self_id else playlist.owner_name
        entries.append(
            LibraryEntry(playlist.id, playlist.name, f"Playlist • {owner}", playlist.cover_seed)
        )
    return tuple(entries)


@dataclass(frozen=True)
class SearchResults:
    tracks: tuple[Track, ...]
    artists: tuple[Artist, ...]
    playlists: tuple[Playlist, ...]

    @property
    def empty(self) -> bool:
        return not (self.tracks or self.artists or self.playlists)


@per_state()
def search(music: Music, q: str) -> SearchResults:
    """Tracks by title, artist, album or genre; artists by name or genre; playlists by name
    (case-insensitive)."""
    needle = q.strip().lower()
    if not needle:
        return SearchResults((), (), ())
    return SearchResults(
        tracks=tuple(
            t
            for t in trending(music)
            if needle in t.title.lower()
            or needle in t.artist_name.lower()
            or needle in t.album.lower()
            or needle in t.genre.lower()
        ),
        artists=tuple(
            a for a in top_artists(music) if needle in a.name.lower() or needle in a.genre.lower()
        ),
        playlists=tuple(
            p
            for p in (*music.playlists.values(), *music.user_playlists.values())
            if needle in p.name.lower()
        ),
    )


@dataclass(frozen=True)
class Player:
    """The bottom bar: what is playing and how far it got (shown in PLAYER_STEP_S steps)."""

    track: Track
    position_s: float
    playing: bool

    @property
    def percent(self) -> float:
        return (
            round(100 * self.position_s / self.track.duration_s, 1) if self.track.duration_s else 0
        )


def player(music: Music, now: float) -> tuple[Player | None, float | None]:
    """The player bar at `now`, and when what it shows next changes (None: never).

    A track made unavailable stops, as on Spotify: the bar shows nothing playing (MicroFy has no
    queue to move on to), and playing it again is refused (`apps.kit.deciding.found`)."""
    playing = music.now_playing
    if playing is None or not still_there(music.tracks, playing.track_id):
        return None, None
    track = music.tracks[playing.track_id]
    elapsed = max(0.0, now - playing.started_at)
    if elapsed >= track.duration_s:
        return Player(track, float(track.duration_s), False), None
    steps = math.floor(elapsed / PLAYER_STEP_S)
    next_step = playing.started_at + (steps + 1) * PLAYER_STEP_S
    end = playing.started_at + track.duration_s
    return Player(track, steps * PLAYER_STEP_S, True), min(next_step, end)
