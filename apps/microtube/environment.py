"""MicroTube's registration with the core: scenario events, baselines, evaluation tables.

Scenario events (SentinelBench format):
- `preload_videos {video_ids, channel_ids, comment_ids, notification_ids,
  subscribed_channel_ids, watched_video_ids}` — all optional, each takes `["*"]` (the whole
  catalog table). A subscribed channel is loaded if needed; a watched video brings its channel.
  Baselines are captured right after it applies.
- `new_video {video_id}` — an upload appears (with its channel, if that was not loaded: the
  original left such a video without a channel page).
- `new_comment {comment_id}`, `new_notification {notification_id}`.
- `make_private {video_id}` — its uploader makes a video private now (apps.kit.retractions).

Ids missing from the catalog are skipped (the original raised); scenario validation reports them
to the author before a run starts.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from apps.kit.arrivals import Delivery, arrival, event_types, preload
from apps.kit.counts import ShownCount, item_on_screen
from apps.kit.deciding import opening
from apps.kit.environments import declare
from apps.kit.retractions import retraction, still_there, window
from apps.kit.streaming import read_at
from apps.kit.tables import KEY, Table, named, tables
from apps.microtube import screens as tube_screens
from apps.microtube import state as tube_state
from apps.microtube.catalog import (
    catalog_channel,
    catalog_comment,
    catalog_notification,
    catalog_video,
)
from apps.microtube.state import (
    ENVIRONMENT,
    ChannelState,
    Tube,
    VideoState,
    empty_tube,
    with_subscription,
    with_watched,
)
from events.registry import counted

# Counted right after the preload, by the core (eval_sql reads baseline_<name>). The original
# captures the first six; `video_count` is read by its video-total-relative-passive scenario.
BASELINES = counted(
    {
        "subscribed_count": tube_state.subscribed_count,
        "liked_count": tube_state.liked_count,
        "watched_count": tube_state.watched_count,
        "comment_count": tube_state.comment_count,
        "notification_count": tube_state.notification_count,
        "playlist_count": tube_state.playlist_count,
        "video_count": tube_state.video_count,
    }
)

deliver_channels = Delivery(
    "channels", catalog_channel, states="channel_states", fresh=ChannelState
)
deliver_uploads = Delivery("videos", catalog_video, states="video_states", fresh=VideoState)


def deliver_videos(tube: Tube, video_ids: Iterable[str], at: float, *, preloaded: bool) -> Tube:
    """Catalog videos not yet loaded, and the channel of each."""
    video_ids = list(video_ids)
    tube = deliver_uploads(tube, video_ids, at, preloaded=preloaded)
    channel_ids = [tube.videos[v].channel_id for v in video_ids if v in tube.videos]
    return deliver_channels(tube, channel_ids, at, preloaded=preloaded)


def subscribe_and_watch(tube: Tube, payload: Mapping[str, Any], at: float) -> Tube:
    """The preload's subscriptions (not the user's doing: the shown counts stay) and history."""
    catalog = tube.catalog
    for channel_id in catalog.expand(
        ENVIRONMENT, "channels", payload.get("subscribed_channel_ids")
    ):
        tube = with_subscription(tube, channel_id, True, by_user=False)
    return with_watched(
        tube, catalog.expand(ENVIRONMENT, "videos", payload.get("watched_video_ids"))
    )


deliver_comments = Delivery("comments", catalog_comment)
deliver_notifications = Delivery(
    "notifications", catalog_notification, states="notification_states"
)

EVENT_TYPES = event_types(
    preload(
        "preload_videos",
        {
            "channel_ids": ("channels", deliver_channels),
            "subscribed_channel_ids": ("channels", deliver_channels),
            "video_ids": ("videos", deliver_videos),
            "watched_video_ids": ("videos", deliver_videos),
            "comment_ids": ("comments", deliver_comments),
            "notification_ids": ("notifications", deliver_notifications),
        },
        then=subscribe_and_watch,
        environment=ENVIRONMENT,
        help="Videos, channels, subscriptions, comments, notifications and history at the "
        "start; baselines are measured after it.",
    ),
    arrival(
        "new_video",
        "video_id",
        "videos",
        deliver_videos,
        help="A channel uploads a video: it appears on Home, Subscriptions and the channel.",
    ),
    retraction(
        "make_private",
        "video_id",
        "videos",
        "videos",
        help="Its uploader makes a video private: it leaves every list but playlists, where it "
        'stays as "[Private video]"; its watch page says "Video unavailable. This video is '
        'private."',
    ),
    arrival(
        "new_comment",
        "comment_id",
        "comments",
        deliver_comments,
        help="Someone comments on a video.",
    ),
    arrival(
        "new_notification",
        "notification_id",
        "notifications",
        deliver_notifications,
        help="A notification arrives in the bell, unread.",
    ),
)


# --- evaluation tables (the original's names and columns, so eval_sql runs unchanged) -----------
# Views, likes and subscribers are read at `now` (the numbers the page shows at that instant);
# `channels.subscribers` leaves out the user's own subscription, as the original's table does.


materialize = tables(
    Table(
        "videos",
        read_at(lambda tube: tube.videos.values()),
        {
            **named("id TEXT PRIMARY KEY", "channel_id TEXT", "title TEXT"),
            "views INTEGER": lambda v: v.view_count(v.now),
            "likes INTEGER": lambda v: v.like_count(v.now),
            "isLive INTEGER": "is_live",
            "isShort INTEGER": "is_short",
            **window("arrived_at"),
        },
    ),
    Table.keyed(
        "video_states",
        "video_states",
        {
            "video_id TEXT PRIMARY KEY": KEY,
            "isLiked INTEGER": "liked",
            "isDisliked INTEGER": "disliked",
            "isSaved INTEGER": "saved",
        },
    ),
    Table(
        "channels",
        read_at(lambda tube: tube.channels.values()),
        {
            **named("id TEXT PRIMARY KEY", "name TEXT", "handle TEXT"),
            "subscribers INTEGER": lambda c: c.subscriber_count(c.now),
            "isVerified INTEGER": "verified",
        },
    ),
    Table.keyed(
        "channel_states",
        "channel_states",
        {"channel_id TEXT PRIMARY KEY": KEY, "isSubscribed INTEGER": "subscribed"},
    ),
    Table.items(
        "comments",
        named(
            "id TEXT PRIMARY KEY", "video_id TEXT", "user_id TEXT", "content TEXT", "likes INTEGER"
        ),
    ),
    Table.items(
        "notifications",
        {
            **named("id TEXT PRIMARY KEY", "type TEXT"),
            "channel_id TEXT": lambda n: n.channel_id or None,
            "message TEXT": "message",
        },
    ),
    Table.keyed(
        "notification_states",
        "notification_states",
        {
            "notification_id TEXT PRIMARY KEY": KEY,
            "isDismissed INTEGER": "dismissed",
            "isRead INTEGER": "read",
        },
    ),
    Table.items(
        "user_created_comments",
        named("id TEXT PRIMARY KEY", "video_id TEXT", "content TEXT"),
        "user_comments",
    ),
    Table.items(
        "user_created_playlists",
        named("id TEXT PRIMARY KEY", "name TEXT", "data TEXT"),
        "playlists",
    ),
    Table(
        "watched_videos", lambda tube, now: tube.watched, {"video_id TEXT PRIMARY KEY": lambda v: v}
    ),
)


def _on_screen(path: str, page: str, key: str) -> str:
    """The id a page shows: `watch?v=ID` → ID for ("watch", "v"); "" on any other page."""
    name, _, query = path.partition("?")
    if name != page:
        return ""
    return next((v for k, _, v in (p.partition("=") for p in query.split("&")) if k == key), "")


# The numbers shown in more than one place (apps.kit.counts): a channel's video count in its
# header and its About box, a video's comment count. (The bell reads "9+" past nine.)
SHOWN_COUNTS = (
    ShownCount(
        "videos of the channel on screen",
        lambda tube, now: 0,
        ("{n} videos?",),
        on=lambda tube, path: bool(item_on_screen(path, "channel/")),
        value_on=lambda tube, now, path: (
            tube.channels[item_on_screen(path, "channel/")].video_total
        ),
    ),
    ShownCount(
        "comments on the video on screen",
        lambda tube, now: 0,
        ("{n} Comments?",),
        on=lambda tube, path: bool(_on_screen(path, "watch", "v")),
        value_on=lambda tube, now, path: len(
            tube_screens.comments(tube, _on_screen(path, "watch", "v"))
        ),
    ),
)


def not_watched_yet(tube: Tube, video_id: str) -> bool:
    return still_there(tube.videos, video_id) and video_id not in tube.watched


IMPLICIT_ACTIONS = (
    # Opening a video's watch page is watching it (however the page was reached: the
    # original counted only clicks inside its own feed).
    opening("watch", "v", "watch_video", "video_id", applies=not_watched_yet),
)


MICROTUBE = declare(__name__, title="MicroTube", initial_state=empty_tube)
