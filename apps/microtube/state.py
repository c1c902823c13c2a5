"""The video site as immutable values, and the questions pages and baselines ask of it.

`Tube` is what the reducers build: the videos, channels, comments and notifications that have
arrived, in arrival order, and what the self user did to them (ratings, saves, subscriptions,
comments, playlists, watch history). It is never mutated. View, like and subscriber counts move
with the clock: each is a `Waypoints` series read at the one `now` of a request, so the page, its
live push and the evaluation tables show the same number at the same simulated instant.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import Any

from apps.kit.waypoints import Waypoints

ENVIRONMENT = "microtube"
EMPTY: Mapping = MappingProxyType({})
SELF_CHANNEL = "ch-self"  # the original's fixed id of the self user's channel
WATCH_LATER = "WL"  # YouTube's ids of the two built-in lists
LIKED_VIDEOS = "LL"
FALLBACK_SELF: Mapping[str, Any] = MappingProxyType({"name": "You", "username": "you"})


def shown_count(value: float) -> int:
    """A moving count as a whole number (half rounds up, as `Waypoints.next_change` assumes)."""
    return math.floor(value + 0.5)


@dataclass(frozen=True)
class Channel:
    id: str
    name: str
    handle: str
    description: str
    subscribers: Waypoints  # the catalog's count, drifting with the clock
    video_total: int  # "342 videos" on the channel header (the catalog's number)
    verified: bool = False
    is_self: bool = False
    owner_id: str = ""  # the persona who runs it (users.json), when one does

    def subscriber_count(self, now: float) -> int:
        return shown_count(self.subscribers.value_at(now))


@dataclass(frozen=True)
class Video:
    id: str
    channel_id: str
    title: str
    description: str
    duration: str  # "24:30", as catalogued
    thumbnail_subject: str  # the apps.media picture subject drawn for it
    views: Waypoints
    likes: Waypoints
    dislikes: int = 0
    is_live: bool = False
    is_short: bool = False
    category: str = ""
    published_at: float = 0.0  # simulated seconds (negative: before the run started)
    arrived_at: float = 0.0
    uploaded: bool = False  # arrived during the run (new_video), not preloaded

    def view_count(self, now: float) -> int:
        return shown_count(self.views.value_at(now))

    def like_count(self, now: float) -> int:
        return shown_count(self.likes.value_at(now))


@dataclass(frozen=True)
class VideoState:
    liked: bool = False
    disliked: bool = False
    saved: bool = False  # Watch later


@dataclass(frozen=True)
class ChannelState:
    subscribed: bool = False
    # The user's own effect on the shown count: +1 per subscribe, −1 per unsubscribe (the
    # original's effective `subscribers`; the evaluation table keeps the catalog count).
    adjustment: int = 0


@dataclass(frozen=True)
class Comment:
    id: str
    video_id: str
    user_id: str
    author: str
    content: str
    likes: int = 0
    replies: int = 0
    posted_at: float = 0.0
    by_self: bool = False


@dataclass(frozen=True)
class Notification:
    id: str
    type: str  # upload | live | comment | community | mention
    channel_id: str
    video_id: str
    message: str
    arrived_at: float = 0.0


@dataclass(frozen=True)
class NotificationState:
    read: bool = False
    dismissed: bool = False


@dataclass(frozen=True)
class Playlist:
    id: str
    name: str
    video_ids: tuple[str, ...] = ()
    created_at: float = 0.0


@dataclass(frozen=True)
class Tube:
    # The catalog and self user are inputs, not state: excluded from equality.
    catalog: Any = field(compare=False, repr=False)
    self_user: Mapping[str, Any] = field(
        compare=False, repr=False, default_factory=lambda: FALLBACK_SELF
    )
    videos: Mapping[str, Video] = field(default_factory=lambda: EMPTY)
    video_states: Mapping[str, VideoState] = field(default_factory=lambda: EMPTY)
    channels: Mapping[str, Channel] = field(default_factory=lambda: EMPTY)
    channel_states: Mapping[str, ChannelState] = field(default_factory=lambda: EMPTY)
    comments: Mapping[str, Comment] = field(default_factory=lambda: EMPTY)  # scenario comments
    user_comments: Mapping[str, Comment] = field(default_factory=lambda: EMPTY)
    notifications: Mapping[str, Notification] = field(default_factory=lambda: EMPTY)
    notification_states: Mapping[str, NotificationState] = field(default_factory=lambda: EMPTY)
    playlists: Mapping[str, Playlist] = field(default_factory=lambda: EMPTY)
    watched: tuple[str, ...] = ()  # video ids in the order first watched

    @property
    def self_name(self) -> str:
        return str(self.self_user.get("name") or FALLBACK_SELF["name"])

    @property
    def self_id(self) -> str:
        return str(self.self_user.get("id") or "user000")

    def is_subscribed(self, channel_id: str) -> bool:
        state = self.channel_states.get(channel_id)
        return state is not None and state.subscribed

    def shown_subscribers(self, channel_id: str, now: float) -> int:
        """The count the pages show: the drifting catalog count plus the user's own +1."""
        channel, state = self.channels[channel_id], self.channel_states[channel_id]
        return max(0, channel.subscriber_count(now) + state.adjustment)


def empty_tube(catalog: Any) -> Tube:
    return Tube(catalog=catalog, self_user=getattr(catalog, "self_user", None) or FALLBACK_SELF)


# --- building new states (reducers only) ---------------------------------------------------------


def _with(mapping: Mapping, key: str, value: Any) -> Mapping:
    changed = dict(mapping)
    changed[key] = value
    return MappingProxyType(changed)


def with_channels(tube: Tube, channels: Iterable[Channel]) -> Tube:
    """Add channels not yet loaded (a channel already there keeps its state)."""
    added = {c.id: c for c in channels if c.id not in tube.channels}
    if not added:
        return tube
    states = {cid: ChannelState() for cid in added}
    return replace(
        tube,
        channels=MappingProxyType({**tube.channels, **added}),
        channel_states=MappingProxyType({**tube.channel_states, **states}),
    )


def with_videos(tube: Tube, videos: Iterable[Video]) -> Tube:
    added = {v.id: v for v in videos if v.id not in tube.videos}
    if not added:
        return tube
    return replace(
        tube,
        videos=MappingProxyType({**tube.videos, **added}),
        video_states=MappingProxyType(
            {**tube.video_states, **{vid: VideoState() for vid in added}}
        ),
    )


def with_comments(tube: Tube, comments: Iterable[Comment]) -> Tube:
    added = {c.id: c for c in comments if c.id not in tube.comments}
    if not added:
        return tube
    return replace(tube, comments=MappingProxyType({**tube.comments, **added}))


def with_user_comment(tube: Tube, comment: Comment) -> Tube:
    if comment.id in tube.user_comments:
        return tube
    return replace(tube, user_comments=_with(tube.user_comments, comment.id, comment))


def with_notifications(tube: Tube, arrivals: Iterable[tuple[Notification, bool]]) -> Tube:
    """Add notifications (each with its initial read flag), never twice."""
    items = {n.id: (n, read) for n, read in arrivals if n.id not in tube.notifications}
    if not items:
        return tube
    return replace(
        tube,
        notifications=MappingProxyType(
            {**tube.notifications, **{nid: n for nid, (n, _) in items.items()}}
        ),
        notification_states=MappingProxyType(
            {
                **tube.notification_states,
                **{nid: NotificationState(read=read) for nid, (_, read) in items.items()},
            }
        ),
    )


def with_video_state(tube: Tube, video_id: str, **changes: Any) -> Tube:
    current = tube.video_states.get(video_id)
    if current is None:
        return tube
    return replace(
        tube, video_states=_with(tube.video_states, video_id, replace(current, **changes))
    )


def with_subscription(tube: Tube, channel_id: str, subscribed: bool, *, by_user: bool) -> Tube:
    """Set a subscription; the user's own (un)subscribe also moves the shown count by one.
    Setting it to what it already is changes nothing."""
    current = tube.channel_states.get(channel_id)
    if current is None or current.subscribed == subscribed:
        return tube
    step = (1 if subscribed else -1) if by_user else 0
    changed = ChannelState(subscribed=subscribed, adjustment=current.adjustment + step)
    return replace(tube, channel_states=_with(tube.channel_states, channel_id, changed))


def with_notification_state(tube: Tube, notification_id: str, **changes: Any) -> Tube:
    current = tube.notification_states.get(notification_id)
    if current is None:
        return tube
    changed = replace(current, **changes)
    return replace(
        tube, notification_states=_with(tube.notification_states, notification_id, changed)
    )


def with_watched(tube: Tube, video_ids: Iterable[str]) -> Tube:
    new = [v for v in dict.fromkeys(video_ids) if v in tube.videos and v not in tube.watched]
    return replace(tube, watched=tube.watched + tuple(new)) if new else tube


def with_playlist(tube: Tube, playlist: Playlist) -> Tube:
    return replace(tube, playlists=_with(tube.playlists, playlist.id, playlist))


# --- counts (baselines and badges) -------------------------------------------------------------


def subscribed_count(tube: Tube) -> int:
    return sum(1 for s in tube.channel_states.values() if s.subscribed)


def liked_count(tube: Tube) -> int:
    return sum(1 for s in tube.video_states.values() if s.liked)


def watched_count(tube: Tube) -> int:
    return len(tube.watched)


def comment_count(tube: Tube) -> int:
    """Scenario comments plus the user's own (the original's baseline)."""
    return len(tube.comments) + len(tube.user_comments)


def notification_count(tube: Tube) -> int:
    """Notifications not dismissed (what the panel lists)."""
    return sum(1 for s in tube.notification_states.values() if not s.dismissed)


def unread_notification_count(tube: Tube) -> int:
    """The bell's badge: unread and not dismissed."""
    return sum(1 for s in tube.notification_states.values() if not s.dismissed and not s.read)


def playlist_count(tube: Tube) -> int:
    return len(tube.playlists)


def video_count(tube: Tube) -> int:
    return len(tube.videos)


def next_user_id(existing: Mapping[str, Any], prefix: str) -> str:
    """`<prefix>-<n>` for the next user-created item (the original's id shape); decided once
    and logged, so replay reuses it."""
    n = len(existing) + 1
    while f"{prefix}-{n}" in existing:
        n += 1
    return f"{prefix}-{n}"
