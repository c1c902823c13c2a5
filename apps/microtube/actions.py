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

from apps.kit.deciding import checking, marking
from apps.kit.fields import ItemId, Line, Text
from apps.kit.state import setting, with_changed, with_items
from apps.kit.streaming import bounded_text, id_payload, numbered_id
from apps.microtube.query import WatchQuery
from apps.microtube.state import Comment, Playlist, Tube, with_subscription, with_watched
from events.registry import Action, ActionRejected, LoggedEvent, PageStep
from events.schemas import Payload

MAX_COMMENT = 10_000
MAX_PLAYLIST_NAME = 150
ON_SITE = "on this site"

VideoId = id_payload("VideoId", "video_id", "id of a video on the site")
ChannelId = id_payload("ChannelId", "channel_id", "id of a channel on the site")
NotificationId = id_payload("NotificationId", "notification_id", "id of a notification in the bell")


class PostComment(VideoId):
    content: Text = Field(description="the comment text")


class CreatePlaylist(Payload):
    name: Line = Field(description="the new playlist's title")
    video_id: ItemId | None = Field(None, description="a video to put in it straight away")


class AddToPlaylist(VideoId):
    playlist_id: ItemId = Field(description="id of one of the user's playlists")


# A 404 for an id the site does not show: unknown and not yet arrived look the same.
video_exists = checking("videos", "video_id", "video", ON_SITE)
channel_exists = checking("channels", "channel_id", "channel", ON_SITE)
notification_exists = checking("notifications", "notification_id", "notification", ON_SITE)


def subscribing(subscribed: bool) -> Callable[[Tube, LoggedEvent], Tube]:
    def reduce(tube: Tube, event: LoggedEvent) -> Tube:
        return with_subscription(tube, event.payload["channel_id"], subscribed, by_user=True)

    return reduce


def reduce_watch(tube: Tube, event: LoggedEvent) -> Tube:
    return with_watched(tube, [event.payload["video_id"]])


def decide_comment(tube: Tube, payload: dict) -> dict:
    video_exists(tube, payload)
    content = bounded_text(
        payload,
        "content",
        MAX_COMMENT,
        empty="a comment cannot be empty",
        too_long=f"a comment is at most {MAX_COMMENT} characters",
    )
    return {
        **payload,
        "content": content,
        "comment_id": numbered_id(tube.user_comments, "user-cmt"),
    }


def reduce_comment(tube: Tube, event: LoggedEvent) -> Tube:
    payload = event.payload
    if payload["comment_id"] in tube.user_comments:
        return tube
    comment = Comment(
        id=payload["comment_id"],
        video_id=payload["video_id"],
        user_id=tube.self_id,
        author=tube.self_name,
        content=payload["content"],
        posted_at=event.at,
        by_self=True,
    )
    return with_items(tube, "user_comments", [(comment.id, comment)])


def decide_create_playlist(tube: Tube, payload: dict) -> dict:
    name = bounded_text(
        payload,
        "name",
        MAX_PLAYLIST_NAME,
        empty="a playlist needs a title",
        too_long=f"a playlist title is at most {MAX_PLAYLIST_NAME} characters",
    )
    if payload.get("video_id") is not None:
        video_exists(tube, payload)
    return {**payload, "name": name, "playlist_id": numbered_id(tube.playlists, "pl-user")}


def reduce_create_playlist(tube: Tube, event: LoggedEvent) -> Tube:
    payload = event.payload
    if payload["playlist_id"] in tube.playlists:
        return tube
    videos = (payload["video_id"],) if payload.get("video_id") else ()
    playlist = Playlist(payload["playlist_id"], payload["name"], videos, created_at=event.at)
    return with_items(tube, "playlists", [(playlist.id, playlist)])


def decide_add_to_playlist(tube: Tube, payload: dict) -> dict:
    video_exists(tube, payload)
    if payload["playlist_id"] not in tube.playlists:
        raise ActionRejected(f"no playlist {payload['playlist_id']!r} of yours", status=404)
    return payload


def reduce_add_to_playlist(tube: Tube, event: LoggedEvent) -> Tube:
    """Append the video unless the playlist already has it (the original's rule)."""
    playlist = tube.playlists.get(event.payload["playlist_id"])
    video_id = event.payload["video_id"]
    if playlist is None or video_id in playlist.video_ids:
        return tube
    return with_changed(tube, "playlists", playlist.id, video_ids=(*playlist.video_ids, video_id))


# --- where a person does each action ---------------------------------------------------------


def watch_page(tube: Tube, payload: dict, form: Mapping[str, str] | None) -> PageStep:
    video_exists(tube, payload)
    return PageStep("watch" + WatchQuery(v=payload["video_id"]).querystring(), form)


def on_watch_page(*fields: str) -> Callable[[Tube, dict], PageStep]:
    """The action's form on the video's watch page, with `fields` typed in."""

    def page(tube: Tube, payload: dict) -> PageStep:
        return watch_page(tube, payload, {f: payload[f] for f in fields if payload.get(f)})

    return page


def opening_watch_page(tube: Tube, payload: dict) -> PageStep:
    return watch_page(tube, payload, None)  # opening the page is watching


def channel_page(tube: Tube, payload: dict) -> PageStep:
    channel_exists(tube, payload)
    return PageStep(f"channel/{quote(payload['channel_id'])}", {})


def notifications_page(tube: Tube, payload: dict) -> PageStep:
    notification_exists(tube, payload)
    return PageStep("notifications", {"notification_id": payload["notification_id"]})


def create_playlist_page(tube: Tube, payload: dict) -> PageStep:
    """On the watch page of the video going in ("Save" → "New playlist"), else the Playlists
    page."""
    if payload.get("video_id"):
        return watch_page(tube, payload, {"name": payload["name"]})
    return PageStep("feed/playlists", {"name": payload["name"]})


# The user's rating or save of a video, on its watch page.
rates = marking(VideoId, video_exists, "video_states", "video_id", page=on_watch_page())


def on_notification(help: str, **changes: Any) -> Action:
    reduce = setting("notification_states", "notification_id", **changes)
    return Action(NotificationId, notification_exists, reduce, help=help, page=notifications_page)


def on_channel(help: str, subscribed: bool) -> Action:
    return Action(ChannelId, channel_exists, subscribing(subscribed), help=help, page=channel_page)


ACTIONS: Mapping[str, Action] = MappingProxyType(
    {
        "watch_video": Action(
            VideoId,
            video_exists,
            reduce_watch,
            help="Watch a video (opening its watch page does it); adds it to the history.",
            page=opening_watch_page,
        ),
        "like_video": rates(help="Like a video (clears a dislike).", liked=True, disliked=False),
        "unlike_video": rates(help="Remove your like.", liked=False),
        "dislike_video": rates(help="Dislike a video (clears a like).", disliked=True, liked=False),
        "undislike_video": rates(help="Remove your dislike.", disliked=False),
        "save_video": rates(help="Save to Watch later.", saved=True),
        "unsave_video": rates(help="Remove from Watch later.", saved=False),
        "post_comment": Action(
            PostComment,
            decide_comment,
            reduce_comment,
            help="Comment on a video (a reply is posted as a comment, as in the original).",
            page=on_watch_page("content"),
        ),
        "subscribe": on_channel("Subscribe to a channel (+1 on its shown subscriber count).", True),
        "unsubscribe": on_channel("Unsubscribe from a channel.", False),
        "read_notification": on_notification("Open a notification: it is marked read.", read=True),
        "dismiss_notification": on_notification(
            "Remove a notification from the bell.", dismissed=True
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
