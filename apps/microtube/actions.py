"""What an agent can do on MicroTube: `Action(schema, decide, reduce, page=…)` per action name.

`decide(tube, payload)` checks the request against the current site (unknown or not-yet-arrived
ids are a 404) and returns the payload to log, with any id it chose; `reduce` applies a logged
action and never raises. Ratings, saves and subscriptions are set explicitly (like / unlike,
subscribe / unsubscribe) where the original toggled, so a repeated request or two racing tabs
cannot flip a choice back by accident.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from types import MappingProxyType
from typing import Any
from urllib.parse import quote

from pydantic import Field

from apps.kit.deciding import found
from apps.microtube.query import WatchQuery
from apps.microtube.state import (
    Comment,
    Playlist,
    Tube,
    next_user_id,
    with_notification_state,
    with_playlist,
    with_subscription,
    with_user_comment,
    with_video_state,
    with_watched,
)
from events.registry import Action, ActionRejected, LoggedEvent, PageStep
from events.schemas import Payload

MAX_COMMENT = 10_000
MAX_PLAYLIST_NAME = 150


class VideoId(Payload):
    video_id: str = Field(description="id of a video on the site")


class ChannelId(Payload):
    channel_id: str = Field(description="id of a channel on the site")


class NotificationId(Payload):
    notification_id: str = Field(description="id of a notification in the bell")


class PostComment(VideoId):
    content: str = Field(description="the comment text")


class CreatePlaylist(Payload):
    name: str = Field(description="the new playlist's title")
    video_id: str | None = Field(None, description="a video to put in it straight away")


class AddToPlaylist(VideoId):
    playlist_id: str = Field(description="id of one of the user's playlists")


def existing(tube: Tube, kind: str, item_id: str | None) -> None:
    """A 404 for an id the site does not show: unknown and not yet arrived look the same."""
    label = {"videos": "video", "channels": "channel", "notifications": "notification"}
    found(getattr(tube, kind), item_id, label.get(kind, kind), "on this site")


def checking(kind: str, field: str) -> Callable[[Tube, dict], dict]:
    def decide(tube: Tube, payload: dict) -> dict:
        existing(tube, kind, payload[field])
        return payload

    return decide


def setting_video(**changes: Any) -> Callable[[Tube, LoggedEvent], Tube]:
    def reduce(tube: Tube, event: LoggedEvent) -> Tube:
        return with_video_state(tube, event.payload["video_id"], **changes)

    return reduce


def subscribing(subscribed: bool) -> Callable[[Tube, LoggedEvent], Tube]:
    def reduce(tube: Tube, event: LoggedEvent) -> Tube:
        return with_subscription(tube, event.payload["channel_id"], subscribed, by_user=True)

    return reduce


def setting_notification(**changes: Any) -> Callable[[Tube, LoggedEvent], Tube]:
    def reduce(tube: Tube, event: LoggedEvent) -> Tube:
        return with_notification_state(tube, event.payload["notification_id"], **changes)

    return reduce


def reduce_watch(tube: Tube, event: LoggedEvent) -> Tube:
    return with_watched(tube, [event.payload["video_id"]])


def decide_comment(tube: Tube, payload: dict) -> dict:
    existing(tube, "videos", payload["video_id"])
    content = payload["content"].strip()
    if not content:
        raise ActionRejected("content: a comment cannot be empty")
    if len(content) > MAX_COMMENT:
        raise ActionRejected(f"content: a comment is at most {MAX_COMMENT} characters")
    return {
        **payload,
        "content": content,
        "comment_id": next_user_id(tube.user_comments, "user-cmt"),
    }


def reduce_comment(tube: Tube, event: LoggedEvent) -> Tube:
    payload = event.payload
    comment = Comment(
        id=payload["comment_id"],
        video_id=payload["video_id"],
        user_id=tube.self_id,
        author=tube.self_name,
        content=payload["content"],
        posted_at=event.at,
        by_self=True,
    )
    return with_user_comment(tube, comment)


def playlist_name(payload: dict) -> str:
    name = payload["name"].strip()
    if not name:
        raise ActionRejected("name: a playlist needs a title")
    if len(name) > MAX_PLAYLIST_NAME:
        raise ActionRejected(f"name: a playlist title is at most {MAX_PLAYLIST_NAME} characters")
    return name


def decide_create_playlist(tube: Tube, payload: dict) -> dict:
    name = playlist_name(payload)
    if payload.get("video_id") is not None:
        existing(tube, "videos", payload["video_id"])
    return {**payload, "name": name, "playlist_id": next_user_id(tube.playlists, "pl-user")}


def reduce_create_playlist(tube: Tube, event: LoggedEvent) -> Tube:
    payload = event.payload
    if payload["playlist_id"] in tube.playlists:
        return tube
    videos = (payload["video_id"],) if payload.get("video_id") else ()
    return with_playlist(
        tube, Playlist(payload["playlist_id"], payload["name"], videos, created_at=event.at)
    )


def decide_add_to_playlist(tube: Tube, payload: dict) -> dict:
    existing(tube, "videos", payload["video_id"])
    if payload["playlist_id"] not in tube.playlists:
        raise ActionRejected(f"no playlist {payload['playlist_id']!r} of yours", status=404)
    return payload


def reduce_add_to_playlist(tube: Tube, event: LoggedEvent) -> Tube:
    """Append the video unless the playlist already has it (the original's rule)."""
    playlist = tube.playlists.get(event.payload["playlist_id"])
    video_id = event.payload["video_id"]
    if playlist is None or video_id in playlist.video_ids:
        return tube
    return with_playlist(
        tube,
        Playlist(playlist.id, playlist.name, (*playlist.video_ids, video_id), playlist.created_at),
    )


# --- where a person does each action ---------------------------------------------------------


def watch_page(tube: Tube, payload: dict, form: Mapping[str, str] | None) -> PageStep:
    existing(tube, "videos", payload["video_id"])
    return PageStep("watch" + WatchQuery(v=payload["video_id"]).querystring(), form)


def on_watch_page(*fields: str) -> Callable[[Tube, dict], PageStep]:
    """The action's form on the video's watch page, with `fields` typed in."""

    def page(tube: Tube, payload: dict) -> PageStep:
        return watch_page(tube, payload, {f: payload[f] for f in fields if payload.get(f)})

    return page


def opening_watch_page(tube: Tube, payload: dict) -> PageStep:
    return watch_page(tube, payload, None)  # opening the page is watching


def channel_page(tube: Tube, payload: dict) -> PageStep:
    existing(tube, "channels", payload["channel_id"])
    return PageStep(f"channel/{quote(payload['channel_id'])}", {})


def notifications_page(tube: Tube, payload: dict) -> PageStep:
    existing(tube, "notifications", payload["notification_id"])
    return PageStep("notifications", {"notification_id": payload["notification_id"]})


def create_playlist_page(tube: Tube, payload: dict) -> PageStep:
    """On the watch page of the video going in ("Save" → "New playlist"), else the Playlists
    page."""
    if payload.get("video_id"):
        return watch_page(tube, payload, {"name": payload["name"]})
    return PageStep("feed/playlists", {"name": payload["name"]})


def _video(decide, reduce, help: str, page=None) -> Action:
    return Action(VideoId, decide, reduce, help=help, page=page or on_watch_page())


ACTIONS: Mapping[str, Action] = MappingProxyType(
    {
        "watch_video": _video(
            checking("videos", "video_id"),
            reduce_watch,
            "Watch a video (opening its watch page does it); adds it to the history.",
            page=opening_watch_page,
        ),
        "like_video": _video(
            checking("videos", "video_id"),
            setting_video(liked=True, disliked=False),
            "Like a video (clears a dislike).",
        ),
        "unlike_video": _video(
            checking("videos", "video_id"), setting_video(liked=False), "Remove your like."
        ),
        "dislike_video": _video(
            checking("videos", "video_id"),
            setting_video(disliked=True, liked=False),
            "Dislike a video (clears a like).",
        ),
        "undislike_video": _video(
            checking("videos", "video_id"), setting_video(disliked=False), "Remove your dislike."
        ),
        "save_video": _video(
            checking("videos", "video_id"), setting_video(saved=True), "Save to Watch later."
        ),
        "unsave_video": _video(
            checking("videos", "video_id"),
            setting_video(saved=False),
            "Remove from Watch later.",
        ),
        "post_comment": Action(
            PostComment,
            decide_comment,
            reduce_comment,
            help="Comment on a video (a reply is posted as a comment, as in the original).",
            page=on_watch_page("content"),
        ),
        "subscribe": Action(
            ChannelId,
            checking("channels", "channel_id"),
            subscribing(True),
            help="Subscribe to a channel (+1 on its shown subscriber count).",
            page=channel_page,
        ),
        "unsubscribe": Action(
            ChannelId,
            checking("channels", "channel_id"),
            subscribing(False),
            help="Unsubscribe from a channel.",
            page=channel_page,
        ),
        "read_notification": Action(
            NotificationId,
            checking("notifications", "notification_id"),
            setting_notification(read=True),
            help="Open a notification: it is marked read.",
            page=notifications_page,
        ),
        "dismiss_notification": Action(
            NotificationId,
            checking("notifications", "notification_id"),
            setting_notification(dismissed=True),
            help="Remove a notification from the bell.",
            page=notifications_page,
        ),
        "create_playlist": Action(
            CreatePlaylist,
            decide_create_playlist,
            reduce_create_playlist,
            help="Create a playlist, optionally with the video being watched in it.",
            page=create_playlist_page,
        ),
        "add_to_playlist": Action(
            AddToPlaylist,
            decide_add_to_playlist,
            reduce_add_to_playlist,
            help="Save a video to one of your playlists.",
            page=on_watch_page("playlist_id"),
        ),
    }
)
