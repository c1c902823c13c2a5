"""MicroTube's registration with the core: scenario events, baselines, evaluation tables.

Scenario events (SentinelBench format):
- `preload_videos {video_ids, channel_ids, comment_ids, notification_ids,
  subscribed_channel_ids, watched_video_ids}` — all optional, the first four take `["*"]` (the
  whole catalog table). A subscribed channel is loaded if needed; a watched video brings its
  channel. Baselines are captured right after it applies.
- `new_video {video_id}` — an upload appears (with its channel, if that was not loaded: the
  original left such a video without a channel page).
- `new_comment {comment_id}`, `new_notification {notification_id}`.

Ids missing from the catalog are skipped (the original raised); scenario validation reports them
to the author before a run starts.
"""

from __future__ import annotations

import json
import sqlite3
from collections.abc import Iterable, Mapping
from types import MappingProxyType

from pydantic import Field

from apps.kit.legacy_tables import Table
from apps.microtube import state as tube_state
from apps.microtube.actions import ACTIONS
from apps.microtube.bench import sample_pages
from apps.microtube.catalog import (
    catalog_channel,
    catalog_comment,
    catalog_notification,
    catalog_video,
)
from apps.microtube.state import (
    ENVIRONMENT,
    Tube,
    empty_tube,
    with_channels,
    with_comments,
    with_notifications,
    with_subscription,
    with_videos,
    with_watched,
)
from events.registry import Environment, EventType, ImplicitAction, LoggedEvent, Measure, timeless
from events.schemas import Payload

HOUR = 3600.0

# Counted right after the preload, by the core (eval_sql reads baseline_<name>). The original
# captures the first six; `video_count` is read by its video-total-relative-passive scenario.
BASELINES: Mapping[str, Measure] = MappingProxyType(
    {
        name: timeless(count)
        for name, count in {
            "subscribed_count": tube_state.subscribed_count,
            "liked_count": tube_state.liked_count,
            "watched_count": tube_state.watched_count,
            "comment_count": tube_state.comment_count,
            "notification_count": tube_state.notification_count,
            "playlist_count": tube_state.playlist_count,
            "video_count": tube_state.video_count,
        }.items()
    }
)


def load_channels(tube: Tube, channel_ids: Iterable[str], at: float) -> Tube:
    channels = (catalog_channel(tube.catalog, cid, arrived_at=at) for cid in channel_ids)
    return with_channels(tube, (c for c in channels if c is not None))


def load_videos(tube: Tube, video_ids: Iterable[str], at: float, *, preloaded: bool) -> Tube:
    """Add catalog videos not yet loaded, and the channel of each."""
    videos = [
        v
        for vid in dict.fromkeys(video_ids)
        if vid not in tube.videos
        and (v := catalog_video(tube.catalog, vid, arrived_at=at, preloaded=preloaded)) is not None
    ]
    tube = load_channels(tube, (v.channel_id for v in videos), at)
    return with_videos(tube, videos)


def load_comments(tube: Tube, comment_ids: Iterable[str], at: float, *, preloaded: bool) -> Tube:
    """Scenario comments; preloaded ones were written a few hours before the run."""
    comments = []
    for n, cid in enumerate(dict.fromkeys(comment_ids)):
        posted = at - (1 + n % 9) * HOUR if preloaded else at
        comment = catalog_comment(tube.catalog, cid, arrived_at=posted)
        if comment is not None:
            comments.append(comment)
    return with_comments(tube, comments)


def load_notifications(tube: Tube, notification_ids: Iterable[str], at: float, *, keep_read: bool):
    arrivals = []
    for n, nid in enumerate(dict.fromkeys(notification_ids)):
        arrived = at - (1 + n) * HOUR if keep_read else at
        found = catalog_notification(tube.catalog, nid, arrived_at=arrived)
        if found is not None:
            notification, read = found
            arrivals.append((notification, read and keep_read))
    return with_notifications(tube, arrivals)


def reduce_preload_videos(tube: Tube, event: LoggedEvent) -> Tube:
    """Everything already on the site at the start (the core then measures the baselines)."""
    payload, catalog, at = event.payload, tube.catalog, event.at
    subscribed = list(payload.get("subscribed_channel_ids") or ())
    watched = list(payload.get("watched_video_ids") or ())
    tube = load_channels(
        tube, catalog.expand(ENVIRONMENT, "channels", payload.get("channel_ids")), at
    )
    tube = load_channels(tube, subscribed, at)
    videos = catalog.expand(ENVIRONMENT, "videos", payload.get("video_ids"))
    tube = load_videos(tube, [*videos, *watched], at, preloaded=True)
    for channel_id in subscribed:
        tube = with_subscription(tube, channel_id, True, by_user=False)
    tube = with_watched(tube, watched)
    comments = catalog.expand(ENVIRONMENT, "comments", payload.get("comment_ids"))
    tube = load_comments(tube, comments, at, preloaded=True)
    notifications = catalog.expand(ENVIRONMENT, "notifications", payload.get("notification_ids"))
    return load_notifications(tube, notifications, at, keep_read=True)


def reduce_new_video(tube: Tube, event: LoggedEvent) -> Tube:
    return load_videos(tube, [event.payload["video_id"]], event.at, preloaded=False)


def reduce_new_comment(tube: Tube, event: LoggedEvent) -> Tube:
    return load_comments(tube, [event.payload["comment_id"]], event.at, preloaded=False)


def reduce_new_notification(tube: Tube, event: LoggedEvent) -> Tube:
    """A notification arrives unread."""
    return load_notifications(tube, [event.payload["notification_id"]], event.at, keep_read=False)


class PreloadVideos(Payload):
    video_ids: list[str] = Field(default_factory=list, description='["*"] = every video')
    channel_ids: list[str] = Field(default_factory=list, description='["*"] = every channel')
    comment_ids: list[str] = Field(default_factory=list, description='["*"] = every comment')
    notification_ids: list[str] = Field(
        default_factory=list, description='["*"] = every notification'
    )
    subscribed_channel_ids: list[str] = Field(
        default_factory=list, description="channels the user already follows"
    )
    watched_video_ids: list[str] = Field(
        default_factory=list, description="videos already in the watch history"
    )


class NewVideo(Payload):
    video_id: str = Field(description="catalog video id")


class NewComment(Payload):
    comment_id: str = Field(description="catalog comment id")


class NewNotification(Payload):
    notification_id: str = Field(description="catalog notification id")


EVENT_TYPES: Mapping[str, EventType] = MappingProxyType(
    {
        "preload_videos": EventType(
            schema=PreloadVideos,
            reduce=reduce_preload_videos,
            help="Videos, channels, subscriptions, comments, notifications and history at the "
            "start; baselines are measured after it.",
            catalog_refs={
                "video_ids": "videos",
                "channel_ids": "channels",
                "comment_ids": "comments",
                "notification_ids": "notifications",
                "subscribed_channel_ids": "channels",
                "watched_video_ids": "videos",
            },
            preload=True,
        ),
        "new_video": EventType(
            schema=NewVideo,
            reduce=reduce_new_video,
            help="A channel uploads a video: it appears on Home, Subscriptions and the channel.",
            catalog_refs={"video_id": "videos"},
        ),
        "new_comment": EventType(
            schema=NewComment,
            reduce=reduce_new_comment,
            help="Someone comments on a video.",
            catalog_refs={"comment_id": "comments"},
        ),
        "new_notification": EventType(
            schema=NewNotification,
            reduce=reduce_new_notification,
            help="A notification arrives in the bell, unread.",
            catalog_refs={"notification_id": "notifications"},
        ),
    }
)


# --- evaluation tables (the original's names and columns, so eval_sql runs unchanged) -----------

VIDEOS = Table(
    "videos",
    (
        "id TEXT PRIMARY KEY",
        "channel_id TEXT",
        "title TEXT",
        "views INTEGER",
        "likes INTEGER",
        "isLive INTEGER",
        "isShort INTEGER",
    ),
)
VIDEO_STATES = Table(
    "video_states",
    ("video_id TEXT PRIMARY KEY", "isLiked INTEGER", "isDisliked INTEGER", "isSaved INTEGER"),
)
CHANNELS = Table(
    "channels",
    (
        "id TEXT PRIMARY KEY",
        "name TEXT",
        "handle TEXT",
        "subscribers INTEGER",
        "isVerified INTEGER",
    ),
)
CHANNEL_STATES = Table("channel_states", ("channel_id TEXT PRIMARY KEY", "isSubscribed INTEGER"))
COMMENTS = Table(
    "comments",
    ("id TEXT PRIMARY KEY", "video_id TEXT", "user_id TEXT", "content TEXT", "likes INTEGER"),
)
NOTIFICATIONS = Table(
    "notifications", ("id TEXT PRIMARY KEY", "type TEXT", "channel_id TEXT", "message TEXT")
)
NOTIFICATION_STATES = Table(
    "notification_states",
    ("notification_id TEXT PRIMARY KEY", "isDismissed INTEGER", "isRead INTEGER"),
)
USER_CREATED_COMMENTS = Table(
    "user_created_comments", ("id TEXT PRIMARY KEY", "video_id TEXT", "content TEXT")
)
USER_CREATED_PLAYLISTS = Table(
    "user_created_playlists", ("id TEXT PRIMARY KEY", "name TEXT", "data TEXT")
)
WATCHED_VIDEOS = Table("watched_videos", ("video_id TEXT PRIMARY KEY",))


def materialize(tube: Tube, now: float, conn: sqlite3.Connection) -> None:
    """Write the original's ten tables. Views, likes and subscribers are read at `now` (the
    numbers the page shows at that instant); `channels.subscribers` leaves out the user's own
    subscription, as the original's table does."""
    VIDEOS.write(
        conn,
        (
            (
                v.id,
                v.channel_id,
                v.title,
                v.view_count(now),
                v.like_count(now),
                v.is_live,
                v.is_short,
            )
            for v in tube.videos.values()
        ),
    )
    VIDEO_STATES.write(
        conn, ((vid, s.liked, s.disliked, s.saved) for vid, s in tube.video_states.items())
    )
    CHANNELS.write(
        conn,
        (
            (c.id, c.name, c.handle, c.subscriber_count(now), c.verified)
            for c in tube.channels.values()
        ),
    )
    CHANNEL_STATES.write(conn, ((cid, s.subscribed) for cid, s in tube.channel_states.items()))
    COMMENTS.write(
        conn, ((c.id, c.video_id, c.user_id, c.content, c.likes) for c in tube.comments.values())
    )
    NOTIFICATIONS.write(
        conn,
        ((n.id, n.type, n.channel_id or None, n.message) for n in tube.notifications.values()),
    )
    NOTIFICATION_STATES.write(
        conn,
        ((nid, s.dismissed, s.read) for nid, s in tube.notification_states.items()),
    )
    USER_CREATED_COMMENTS.write(
        conn, ((c.id, c.video_id, c.content) for c in tube.user_comments.values())
    )
    USER_CREATED_PLAYLISTS.write(
        conn,
        (
            (p.id, p.name, json.dumps({"id": p.id, "name": p.name, "video_ids": list(p.video_ids)}))
            for p in tube.playlists.values()
        ),
    )
    WATCHED_VIDEOS.write(conn, ((vid,) for vid in tube.watched))


MICROTUBE = Environment(
    name=ENVIRONMENT,
    title="MicroTube",
    initial_state=empty_tube,
    event_types=EVENT_TYPES,
    actions=ACTIONS,
    baselines=BASELINES,
    materialize=materialize,
    urlconf="apps.microtube.urls",
    implicit_actions=(
        # Opening a video's watch page is watching it (however the page was reached: the
        # original counted only clicks inside its own feed).
        ImplicitAction(
            page="watch",
            param="v",
            action="watch_video",
            payload=lambda video_id: {"video_id": video_id},
            applies=lambda tube, video_id: video_id in tube.videos and video_id not in tube.watched,
        ),
    ),
    sample_pages=sample_pages,
)
