"""Turning catalog records (SentinelBench format) into tracks, artists, playlists and moods.

Catalog tables: `microfy/tracks.jsonl`, `playlists.jsonl`, `moods.jsonl` (the original's) and
our `artists.jsonl`. The original kept its artist catalog outside the scenario catalog; with no
`artists` table (its own catalog), artists are derived from the tracks' artistId/artistName.

Counts that drift. The original showed a track's catalog `playCount` as a constant and drew an
artist's "monthly listeners" and followers from Math.random on every render. We keep the
catalog values as the starting point and let them grow linearly over the session at a rate
derived from the record (a `Waypoints` ramp to the timeline's end, held after it), so the page,
its live pushes and the evaluation tables show the same number at the same simulated instant.
"""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType
from typing import Any

from apps.kit.arrivals import Stamp
from apps.kit.records import reader
from apps.kit.streaming import whole
from apps.kit.waypoints import Waypoints
from apps.microfy.state import ENVIRONMENT, UNKNOWN_ARTIST, Artist, Mood, Playlist, Track

HORIZON_S = 720.0  # the original's event_timeline_end: drifting counts stop growing there


def ramp(start: float, per_second: float, *, since: float = 0.0) -> Waypoints:
    """A count of `start` at `since` growing by `per_second` until HORIZON_S."""
    if since >= HORIZON_S:
        return Waypoints(start)
    end = start + per_second * (HORIZON_S - since)
    return Waypoints(start, ((since, start), (HORIZON_S, end)))


def _play_rate(play_count: int) -> float:
    # A few plays a second at most: a big hit visibly ticks, a niche track barely moves.
    return 0.1 + min(play_count, 5_000_000) / 10_000_000


def _plays(catalog: Any, record: Mapping[str, Any], stamp: Stamp) -> Waypoints:
    """Everyone's plays of a track, from its catalog count when it reached the session."""
    plays = whole(record.get("playCount"))
    return ramp(plays, _play_rate(plays), since=max(0.0, stamp.at))


# A track as it arrives (not liked, never played: `TrackState()`); None if the catalog lacks it.
catalog_track = reader(
    ENVIRONMENT,
    "tracks",
    Track,
    plays=_plays,
    arrived_at=lambda catalog, record, stamp: stamp.at,
    preloaded=lambda catalog, record, stamp: stamp.preloaded,
)
catalog_playlist = reader(ENVIRONMENT, "playlists", Playlist)
catalog_mood = reader(ENVIRONMENT, "moods", Mood)


def artists(catalog: Any) -> Mapping[str, Artist]:
    """Every artist: the `artists` table, else one per artistId of the tracks (computed once
    per catalog through `catalog.index`)."""
    found: dict[str, Artist] = {}
    for record in catalog.table(ENVIRONMENT, "artists").values():
        found[str(record["id"])] = _artist(
            str(record["id"]),
            str(record.get("name") or UNKNOWN_ARTIST),
            str(record.get("genre", "")),
            str(record.get("bio", "")),
            whole(record.get("monthlyListeners")),
            whole(record.get("followerCount")),
        )
    for record in catalog.table(ENVIRONMENT, "tracks").values():
        artist_id = str(record.get("artistId", ""))
        if artist_id and artist_id not in found:
            name = str(record.get("artistName") or UNKNOWN_ARTIST)
            found[artist_id] = _artist(artist_id, name, str(record.get("genre", "")), "", 0, 0)
    return MappingProxyType(found)


def _artist(
    artist_id: str, name: str, genre: str, bio: str, listeners: int, followers: int
) -> Artist:
    # An artist without catalog numbers (the original's catalog) starts from a size derived
    # from the id, so the page still reads like a real profile.
    seed = sum(map(ord, artist_id))
    listeners = listeners or 40_000 + (seed * 7_919) % 3_000_000
    followers = followers or listeners // 6
    return Artist(
        id=artist_id,
        name=name,
        genre=genre,
        bio=bio or f"{name} makes {genre.lower() or 'music'}.",
        listeners=ramp(listeners, 0.2 + listeners / 20_000_000),
        followers=ramp(followers, 0.05 + followers / 40_000_000),
    )


def tracks_by_artist(catalog: Any) -> Mapping[str, tuple[str, ...]]:
    """Catalog track ids per artist id, in catalog order."""
    grouped: dict[str, list[str]] = {}
    for track_id, record in catalog.table(ENVIRONMENT, "tracks").items():
        grouped.setdefault(str(record.get("artistId", "")), []).append(track_id)
    return MappingProxyType({k: tuple(v) for k, v in grouped.items()})
