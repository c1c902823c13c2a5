"""Catalog records (SentinelBench format) → channels, videos, comments and notifications.

Tables in `microtube/`: `channels.jsonl`, `videos.jsonl`, `comments.jsonl`,
`notifications.jsonl`, in the original's record shapes (accepted as they are). Our catalog may
add, per video, `thumbnailSubject` (the apps.media picture drawn for it), `publishedAgo`
(seconds before the run) and `viewGrowth` / `likeGrowth`, and per channel `subscriberGrowth`
and `ownerId`: `[[seconds after arrival, count], …]`, how a count climbs while a run lasts. A
record without growth points keeps its catalogued count, which is the original's behaviour.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from apps.kit.waypoints import Waypoints
from apps.microtube.state import (
    ENVIRONMENT,
    SELF_CHANNEL,
    Channel,
    Comment,
    Notification,
    Video,
)

DAY = 86400.0
# The original's categories (and ours) → the apps.media picture subject of the thumbnail.
SUBJECT_BY_CATEGORY: Mapping[str, str] = {
    "tech": "screenshot",
    "education": "screenshot",
    "gaming": "screenshot",
    "news": "office",
    "science": "abstract",
    "cooking": "food",
    "food": "food",
    "fitness": "people",
    "travel": "landscape",
    "diy": "office",
    "auto": "city",
    "autos": "city",
    "history": "landscape",
    "comedy": "people",
    "fashion": "people",
    "pets": "pet",
    "finance": "chart",
    "movies": "city",
    "film": "city",
    "sports": "people",
    "music": "product",
    "lifestyle": "people",
    "language": "city",
}


def _int(value: Any, default: int = 0) -> int:
    try:
        return int(value)
    except (TypeError, ValueError):
        return default


def growth_series(start: float, growth: Any, arrived_at: float) -> Waypoints:
    """`start` until the item arrives, then along its growth points (seconds after arrival)."""
    if not growth:
        return Waypoints(start)
    points = [(arrived_at, start)] + [(arrived_at + float(dt), float(v)) for dt, v in growth]
    return Waypoints(start).with_points(points)


def catalog_channel(catalog: Any, channel_id: str, *, arrived_at: float) -> Channel | None:
    """The channel as loaded at `arrived_at`. The channel marked isSelf shows the self user's
    name and handle, as the original substitutes them."""
    record = catalog.table(ENVIRONMENT, "channels").get(channel_id)
    if record is None:
        return None
    is_self = bool(record.get("isSelf")) or channel_id == SELF_CHANNEL
    me = getattr(catalog, "self_user", None) or {}
    name, handle = str(record.get("name", "")), str(record.get("handle", ""))
    if is_self and me:
        name = str(me.get("name") or name)
        handle = f"@{me['username']}" if me.get("username") else handle
    start = float(_int(record.get("subscribers")))
    return Channel(
        id=channel_id,
        name=name,
        handle=handle,
        description=str(record.get("description", "")),
        subscribers=growth_series(start, record.get("subscriberGrowth"), arrived_at),
        video_total=_int(record.get("videos")),
        verified=bool(record.get("isVerified", False)),
        is_self=is_self,
        owner_id=str(record.get("ownerId") or (me.get("id", "") if is_self else "")),
    )


def _published_at(record: Mapping[str, Any], arrived_at: float, preloaded: bool) -> float:
    """A new upload is published when it arrives; a preloaded one `publishedAgo` before the
    run (or, for a record without it, an age cycling with its catalog order, as the original's
    labels do)."""
    if not preloaded:
        return arrived_at
    ago = record.get("publishedAgo")
    if ago is None:
        ago = (1 + (_int(record.get("order"), 1) * 5) % 27) * DAY
    return arrived_at - float(ago)


def catalog_video(
    catalog: Any, video_id: str, *, arrived_at: float, preloaded: bool
) -> Video | None:
    record = catalog.table(ENVIRONMENT, "videos").get(video_id)
    if record is None:
        return None
    category = str(record.get("category") or "")
    subject = str(record.get("thumbnailSubject") or SUBJECT_BY_CATEGORY.get(category, "abstract"))
    return Video(
        id=video_id,
        channel_id=str(record.get("channel_id", "")),
        title=str(record.get("title", "")),
        description=str(record.get("description", "")),
        duration=str(record.get("duration") or "0:00"),
        thumbnail_subject=subject,
        views=growth_series(float(_int(record.get("views"))), record.get("viewGrowth"), arrived_at),
        likes=growth_series(float(_int(record.get("likes"))), record.get("likeGrowth"), arrived_at),
        dislikes=_int(record.get("dislikes")),
        is_live=bool(record.get("isLive", False)),
        is_short=bool(record.get("isShort", False)),
        category=category,
        published_at=_published_at(record, arrived_at, preloaded),
        arrived_at=float(arrived_at),
        uploaded=not preloaded,
    )


def catalog_comment(catalog: Any, comment_id: str, *, arrived_at: float) -> Comment | None:
    record = catalog.table(ENVIRONMENT, "comments").get(comment_id)
    if record is None:
        return None
    user_id = str(record.get("user_id", ""))
    person = catalog.users.get(user_id) or {}
    me = getattr(catalog, "self_user", None) or {}
    return Comment(
        id=comment_id,
        video_id=str(record.get("video_id", "")),
        user_id=user_id,
        author=str(person.get("name") or user_id or "Unknown viewer"),
        content=str(record.get("content", "")),
        likes=_int(record.get("likes")),
        replies=_int(record.get("replies")),
        posted_at=float(arrived_at),
        by_self=bool(me) and user_id == me.get("id"),
    )


def catalog_notification(
    catalog: Any, notification_id: str, *, arrived_at: float
) -> tuple[Notification, bool] | None:
    """The notification and its catalogued read flag."""
    record = catalog.table(ENVIRONMENT, "notifications").get(notification_id)
    if record is None:
        return None
    notification = Notification(
        id=notification_id,
        type=str(record.get("type") or "upload"),
        channel_id=str(record.get("channel_id") or ""),
        video_id=str(record.get("video_id") or ""),
        message=str(record.get("message", "")),
        arrived_at=float(arrived_at),
    )
    return notification, bool(record.get("isRead", False))
