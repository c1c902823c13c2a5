"""The video site as immutable values, and the questions pages and baselines ask of it.

`Tube` is what the reducers build: the videos, channels, comments and notifications that have
arrived, in arrival order, and what the self user did to them (ratings, saves, subscriptions,
comments, playlists, watch history). It is never mutated. View, like and subscriber counts move
with the clock: each is a `Waypoints` series read at the one `now` of a request, so the page, its
live push and the evaluation tables show the same number at the same simulated instant.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, replace
from types import MappingProxyType
from typing import ClassVar

from apps.kit.records import flag, from_catalog, text, text_or, whole_number
from apps.kit.state import SelfUserState, with_changed
from apps.kit.streaming import counting, no_items, shown_count
from apps.kit.waypoints import Waypoints

ENVIRONMENT = "microtube"
SELF_CHANNEL = "ch-self"  # the original's fixed id of the self user's channel
WATCH_LATER = "WL"  # YouTube's ids of the two built-in lists
LIKED_VIDEOS = "LL"


@dataclass(frozen=True)
class Channel:
    id: str
    name: str
    handle: str
    description: str = from_catalog(text("description"))
    subscribers: Waypoints  # the catalog's count, drifting with the clock
    # "342 videos" on the channel header (the catalog's number)
    video_total: int = from_catalog(whole_number("videos"))
    verified: bool = from_catalog(flag("isVerified"), default=False)
    is_self: bool = False
    owner_id: str = ""  # the persona who runs it (users.json), when one does

    def subscriber_count(self, now: float) -> int:
        return shown_count(self.subscribers.value_at(now))


@dataclass(frozen=True)
class Video:
    id: str
    channel_id: str = from_catalog(text("channel_id"))
    title: str = from_catalog(text("title"))
    description: str = from_catalog(text("description"))
    duration: str = from_catalog(text_or("duration", "0:00"))  # "24:30", as catalogued
    thumbnail_subject: str  # the apps.media picture subject drawn for it
    views: Waypoints
    likes: Waypoints
    dislikes: int = from_catalog(whole_number("dislikes"), default=0)
    is_live: bool = from_catalog(flag("isLive"), default=False)
    is_short: bool = from_catalog(flag("isShort"), default=False)
    category: str = from_catalog(text_or("category"), default="")
    published_at: float = 0.0  # simulated seconds (negative: before the run started)
    arrived_at: float = 0.0
    uploaded: bool = False  # arrived during the run (new_video), not preloaded
    # The words on its thumbnail ("" → the key words of the title).
    thumbnail_text: str = from_catalog(text_or("thumbnailText"), default="")
    gone_at: float | None = None  # made private by its uploader then (apps.kit.retractions)

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
    video_id: str = from_catalog(text("video_id"))
    user_id: str
    author: str
    content: str = from_catalog(text("content"))
    likes: int = from_catalog(whole_number("likes"), default=0)
    replies: int = from_catalog(whole_number("replies"), default=0)
    posted_at: float = 0.0
    by_self: bool = False


@dataclass(frozen=True)
class Notification:
    id: str
    # upload | live | comment | community | mention
    type: str = from_catalog(text_or("type", "upload"))
    channel_id: str = from_catalog(text_or("channel_id"))
    video_id: str = from_catalog(text_or("video_id"))
    message: str = from_catalog(text("message"))
    arrived_at: float = 0.0
    # Who did it, when not the channel (a viewer who commented): their avatar.
    actor: str = from_catalog(text_or("actorName"), default="")
    channel_name: str = ""  # the catalog's, for a channel the run has not loaded


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

    @property
    def data(self) -> str:
        """The original's JSON of a playlist the user created (its table's `data` column)."""
        return json.dumps({"id": self.id, "name": self.name, "video_ids": list(self.video_ids)})


@dataclass(frozen=True)
class Tube(SelfUserState):
    FALLBACK: ClassVar[Mapping[str, str]] = MappingProxyType(
        {"name": "You", "username": "you", "id": "user000"}
    )
    videos: Mapping[str, Video] = no_items()
    video_states: Mapping[str, VideoState] = no_items()
    channels: Mapping[str, Channel] = no_items()
    channel_states: Mapping[str, ChannelState] = no_items()
    comments: Mapping[str, Comment] = no_items()  # scenario comments
    user_comments: Mapping[str, Comment] = no_items()
    notifications: Mapping[str, Notification] = no_items()
    notification_states: Mapping[str, NotificationState] = no_items()
    playlists: Mapping[str, Playlist] = no_items()
    watched: tuple[str, ...] = ()  # video ids in the order first watched

    def is_subscribed(self, channel_id: str) -> bool:
        state = self.channel_states.get(channel_id)
        return state is not None and state.subscribed

    def own_subscription(self, channel_id: str) -> int:
        """What the user adds to a channel's shown count (+1 subscribed); not in its table."""
        state = self.channel_states.get(channel_id)
        return state.adjustment if state is not None else 0


empty_tube = Tube.of  # catalog → the empty site, its self user in place


# --- building new states (reducers only) ---------------------------------------------------------


def with_subscription(tube: Tube, channel_id: str, subscribed: bool, *, by_user: bool) -> Tube:
    """Set a subscription; the user's own (un)subscribe also moves the shown count by one.
    Setting it to what it already is changes nothing."""
    current = tube.channel_states.get(channel_id)
    if current is None or current.subscribed == subscribed:
        return tube
    step = (1 if subscribed else -1) if by_user else 0
    adjustment = current.adjustment + step
    return with_changed(
        tube, "channel_states", channel_id, subscribed=subscribed, adjustment=adjustment
    )


def with_watched(tube: Tube, video_ids: Iterable[str]) -> Tube:
    new = [v for v in dict.fromkeys(video_ids) if v in tube.videos and v not in tube.watched]
    return replace(tube, watched=tube.watched + tuple(new)) if new else tube


# --- counts (baselines and badges) -------------------------------------------------------------

subscribed_count = counting("channel_states", "subscribed")
liked_count = counting("video_states", "liked")
watched_count = counting("watched")
playlist_count = counting("playlists")
video_count = counting("videos")


def comment_count(tube: Tube) -> int:
    """Scenario comments plus the user's own (the original's baseline)."""
    return len(tube.comments) + len(tube.user_comments)


def notification_count(tube: Tube) -> int:
    """Notifications not dismissed (what the panel lists)."""
    return sum(1 for s in tube.notification_states.values() if not s.dismissed)


def unread_notification_count(tube: Tube) -> int:
    """The bell's badge: unread and not dismissed."""
    return sum(1 for s in tube.notification_states.values() if not s.dismissed and not s.read)
