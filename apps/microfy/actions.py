"""What an agent can do in MicroFy: `Action(schema, decide, reduce, page=…)` per action name.

`decide(music, payload)` checks the request against the current library and returns the payload
to log (create_playlist adds the id it chose); `reduce` applies a logged action and never raises.

Differences from the original, on purpose (reference §6): likes and follows are set explicitly
(like / unlike, follow / unfollow) rather than toggled, so a repeated request cannot undo itself;
following needs an artist the user can see (the original accepted any id), and adding to a
playlist needs a track in the session (the original did not check it).
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import replace
from types import MappingProxyType

from pydantic import Field

from apps.kit.deciding import checking
from apps.kit.fields import ItemId, Line, Text
from apps.kit.state import setting, with_changed, with_items
from apps.kit.streaming import bounded_text, id_payload, numbered_id
from apps.microfy import screens
from apps.microfy.state import USER_PLAYLIST_PREFIX, Music, NowPlaying, Playlist, with_followed
from events.registry import Action, ActionRejected, LoggedEvent, PageStep, Reducer
from events.schemas import Payload

NAME_MAX = 100
DESCRIPTION_MAX = 300

TrackId = id_payload("TrackId", "track_id", "id of a track in the session")
ArtistId = id_payload("ArtistId", "artist_id", "id of an artist shown in the session")


class CreatePlaylist(Payload):
    name: Line = Field(description="the new playlist's name (required)")
    description: Text | None = Field(None, description="optional description")


class AddToPlaylist(Payload):
    playlist_id: ItemId = Field(description="id of a playlist the user created")
    track_id: ItemId = Field(description="id of a track in the session")


decide_on_track = checking("tracks", "track_id", "track", "in this session")


def decide_on_artist(music: Music, payload: dict) -> dict:
    if screens.visible_artist(music, payload["artist_id"]) is None:
        raise ActionRejected(f"no artist {payload['artist_id']!r} in this session", status=404)
    return payload


def reduce_play(music: Music, event: LoggedEvent) -> Music:
    """Every press of a play button counts as a play (the original's rule) and starts it."""
    track_id = event.payload["track_id"]
    state = music.states.get(track_id)
    if state is None:
        return music
    music = with_changed(music, "states", track_id, user_play_count=state.user_play_count + 1)
    return replace(music, now_playing=NowPlaying(track_id, event.at))


def following(value: bool) -> Reducer[Music]:
    def reduce(music: Music, event: LoggedEvent) -> Music:
        return with_followed(music, event.payload["artist_id"], value)

    return reduce


def liking(value: bool) -> Reducer[Music]:
    return setting("states", "track_id", is_liked=value)


def decide_create_playlist(music: Music, payload: dict) -> dict:
    name = bounded_text(
        payload,
        "name",
        NAME_MAX,
        empty="a playlist needs a name",
        too_long=f"at most {NAME_MAX} characters",
    )
    description = bounded_text(
        payload, "description", DESCRIPTION_MAX, too_long=f"at most {DESCRIPTION_MAX} characters"
    )
    # The id is chosen here and logged, so replay gives the playlist the same id.
    playlist_id = numbered_id(music.user_playlists, USER_PLAYLIST_PREFIX)
    return {"name": name, "description": description, "playlist_id": playlist_id}


def reduce_create_playlist(music: Music, event: LoggedEvent) -> Music:
    payload = event.payload
    playlist = Playlist(
        id=payload["playlist_id"],
        name=payload["name"],
        description=payload.get("description") or "",
        owner_id=music.self_id,
        owner_name=music.self_name,
        track_ids=(),
    )
    return with_items(music, "user_playlists", [(playlist.id, playlist)])


def decide_add_to_playlist(music: Music, payload: dict) -> dict:
    if not music.owns_playlist(payload["playlist_id"]):
        raise ActionRejected(
            f"no playlist of yours {payload['playlist_id']!r}: only playlists you own "
            "can be added to",
            status=404,
        )
    return decide_on_track(music, payload)


def reduce_add_to_playlist(music: Music, event: LoggedEvent) -> Music:
    """The track goes at the end of one of the user's playlists: one they created, or a catalog
    playlist they own, whose `data` (the evaluation table's copy of its record) says so too."""
    playlist_id, track_id = event.payload["playlist_id"], event.payload["track_id"]
    created = music.user_playlists.get(playlist_id)
    if created is not None:
        if track_id in created.track_ids:
            return music
        track_ids = (*created.track_ids, track_id)
        return with_changed(music, "user_playlists", playlist_id, track_ids=track_ids)
    owned = music.playlists.get(playlist_id)
    if owned is None or owned.owner_id != music.self_id or track_id in owned.track_ids:
        return music
    track_ids = (*owned.track_ids, track_id)
    record = {**json.loads(owned.data or "{}"), "trackIds": list(track_ids)}
    return with_changed(
        music, "playlists", playlist_id, track_ids=track_ids, data=json.dumps(record)
    )


def on_track_page(music: Music, payload: dict) -> PageStep:
    return PageStep(f"track/{payload['track_id']}", {})


def on_artist_page(music: Music, payload: dict) -> PageStep:
    return PageStep(f"artist/{payload['artist_id']}", {})


def on_track(reduce: Reducer[Music], help: str) -> Action:
    return Action(TrackId, decide_on_track, reduce, help=help, page=on_track_page)


def on_artist(followed: bool, help: str) -> Action:
    return Action(ArtistId, decide_on_artist, following(followed), help=help, page=on_artist_page)


ACTIONS: Mapping[str, Action] = MappingProxyType(
    {
        "play_track": on_track(reduce_play, "Play a track (counts a play)."),
        "like_track": on_track(liking(True), "Save a track to Liked Songs."),
        "unlike_track": on_track(liking(False), "Remove a track from Liked Songs."),
        "follow_artist": on_artist(True, "Follow an artist."),
        "unfollow_artist": on_artist(False, "Stop following an artist."),
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
