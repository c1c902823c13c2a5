"""What an agent can do in MicroFy: `Action(schema, decide, reduce, page=…)` per action name.

`decide(music, payload)` checks the request against the current library and returns the payload
to log (create_playlist adds the id it chose); `reduce` applies a logged action and never raises.

Differences from the original, on purpose (reference §6): likes and follows are set explicitly
(like / unlike, follow / unfollow) rather than toggled, so a repeated request cannot undo itself;
following needs an artist the user can see (the original accepted any id), and adding to a
playlist needs a track in the session (the original did not check it).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace
from types import MappingProxyType

from pydantic import Field

from apps.microfy import library
from apps.microfy.state import (
    Music,
    NowPlaying,
    Playlist,
    next_user_playlist_id,
    with_followed,
    with_track_state,
    with_user_playlist,
)
from events.registry import Action, ActionRejected, LoggedEvent, PageStep
from events.schemas import Payload

NAME_MAX = 100
DESCRIPTION_MAX = 300


class TrackId(Payload):
    track_id: str = Field(description="id of a track in the session")


class ArtistId(Payload):
    artist_id: str = Field(description="id of an artist shown in the session")


class CreatePlaylist(Payload):
    name: str = Field(description="the new playlist's name (required)")
    description: str | None = Field(None, description="optional description")


class AddToPlaylist(Payload):
    playlist_id: str = Field(description="id of a playlist the user created")
    track_id: str = Field(description="id of a track in the session")


def decide_on_track(music: Music, payload: dict) -> dict:
    if not music.has(payload["track_id"]):
        raise ActionRejected(f"no track {payload['track_id']!r} in this session", status=404)
    return payload


def decide_on_artist(music: Music, payload: dict) -> dict:
    if library.visible_artist(music, payload["artist_id"]) is None:
        raise ActionRejected(f"no artist {payload['artist_id']!r} in this session", status=404)
    return payload


def reduce_play(music: Music, event: LoggedEvent) -> Music:
    """Every press of a play button counts as a play (the original's rule) and starts it."""
    track_id = event.payload["track_id"]
    state = music.states.get(track_id)
    if state is None:
        return music
    music = with_track_state(music, track_id, user_play_count=state.user_play_count + 1)
    return replace(music, now_playing=NowPlaying(track_id, event.at))


def liking(value: bool):
    def reduce(music: Music, event: LoggedEvent) -> Music:
        return with_track_state(music, event.payload["track_id"], is_liked=value)

    return reduce


def following(value: bool):
    def reduce(music: Music, event: LoggedEvent) -> Music:
        return with_followed(music, event.payload["artist_id"], value)

    return reduce


def decide_create_playlist(music: Music, payload: dict) -> dict:
    name = payload["name"].strip()
    if not name:
        raise ActionRejected("name: a playlist needs a name")
    if len(name) > NAME_MAX:
        raise ActionRejected(f"name: at most {NAME_MAX} characters")
    description = (payload.get("description") or "").strip()
    if len(description) > DESCRIPTION_MAX:
        raise ActionRejected(f"description: at most {DESCRIPTION_MAX} characters")
    # The id is chosen here and logged, so replay gives the playlist the same id.
    return {"name": name, "description": description, "playlist_id": next_user_playlist_id(music)}


def reduce_create_playlist(music: Music, event: LoggedEvent) -> Music:
    payload = event.payload
    playlist = Playlist(
        id=payload["playlist_id"],
        name=payload["name"],
        description=payload.get("description") or "",
        owner_id=music.self_id,
        owner_name=music.self_name,
        track_ids=(),
        user_created=True,
    )
    return with_user_playlist(music, playlist)


def decide_add_to_playlist(music: Music, payload: dict) -> dict:
    if payload["playlist_id"] not in music.user_playlists:
        raise ActionRejected(
            f"no playlist of yours {payload['playlist_id']!r}: only playlists you created "
            "can be added to",
            status=404,
        )
    return decide_on_track(music, payload)


def reduce_add_to_playlist(music: Music, event: LoggedEvent) -> Music:
    playlist = music.user_playlists.get(event.payload["playlist_id"])
    track_id = event.payload["track_id"]
    if playlist is None or track_id in playlist.track_ids:
        return music
    return with_user_playlist(music, replace(playlist, track_ids=(*playlist.track_ids, track_id)))


def on_track_page(music: Music, payload: dict) -> PageStep:
    return PageStep(f"track/{payload['track_id']}", {})


def on_artist_page(music: Music, payload: dict) -> PageStep:
    return PageStep(f"artist/{payload['artist_id']}", {})


ACTIONS: Mapping[str, Action] = MappingProxyType(
    {
        "play_track": Action(
            TrackId,
            decide_on_track,
            reduce_play,
            help="Play a track (counts a play).",
            page=on_track_page,
        ),
        "like_track": Action(
            TrackId,
            decide_on_track,
            liking(True),
            help="Save a track to Liked Songs.",
            page=on_track_page,
        ),
        "unlike_track": Action(
            TrackId,
            decide_on_track,
            liking(False),
            help="Remove a track from Liked Songs.",
            page=on_track_page,
        ),
        "follow_artist": Action(
            ArtistId,
            decide_on_artist,
            following(True),
            help="Follow an artist.",
            page=on_artist_page,
        ),
        "unfollow_artist": Action(
            ArtistId,
            decide_on_artist,
            following(False),
            help="Stop following an artist.",
            page=on_artist_page,
        ),
        "create_playlist": Action(
            CreatePlaylist,
            decide_create_playlist,
            reduce_create_playlist,
            help="Create an empty playlist of your own.",
            page=lambda music, payload: PageStep(
                "", {"name": payload["name"], "description": payload.get("description") or ""}
            ),
        ),
        "add_to_playlist": Action(
            AddToPlaylist,
            decide_add_to_playlist,
            reduce_add_to_playlist,
            help="Add a track to a playlist you created.",
            page=lambda music, payload: PageStep(
                f"track/{payload['track_id']}", {"playlist_id": payload["playlist_id"]}
            ),
        ),
    }
)
