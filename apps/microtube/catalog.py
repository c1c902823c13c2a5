"""Catalog records (SentinelBench format) → channels, videos, comments and notifications.

Tables in `microtube/`: `channels.jsonl`, `videos.jsonl`, `comments.jsonl`,
`notifications.jsonl`, in the original's record shapes (accepted as they are). Our catalog may
add, per video, `thumbnailSubject` (the apps.media picture drawn for it), `thumbnailText` (the
words set large on its thumbnail; without it, the key words of the title), `publishedAgo`
(seconds before the run) and `viewGrowth` / `likeGrowth`, and per channel `subscriberGrowth`
and `ownerId`: `[[seconds after arrival, count], …]`, how a count climbs while a run lasts. A
record without growth points keeps its catalogued count, which is the original's behaviour.
"""

from __future__ import annotations

from collections.abc import Mapping

from apps.kit.arrivals import Stamp
from apps.kit.feeds import from_catalog
from apps.kit.records import Record, read
from apps.kit.streaming import whole
from apps.kit.waypoints import growing
from apps.microtube.state import (
    ENVIRONMENT,
    SELF_CHANNEL,
    Channel,
    Comment,
    Notification,
    NotificationState,
    Tube,
    Video,
)

HOUR, DAY = 3600.0, 86400.0
# The original's categories (and ours) → the apps.media picture subject of the thumbnail.
SUBJECT_BY_CATEGORY: Mapping[str, str] = {
    **dict.fromkeys(("tech", "education", "gaming"), "screenshot"),
    **dict.fromkeys(("news", "diy"), "office"),
    "science": "abstract",
    **dict.fromkeys(("cooking", "food"), "food"),
    **dict.fromkeys(("fitness", "comedy", "fashion", "sports", "lifestyle"), "people"),
    **dict.fromkeys(("travel", "history"), "landscape"),
    **dict.fromkeys(("auto", "autos", "movies", "film", "language"), "city"),
    "pets": "pet",
    "finance": "chart",
    "music": "product",
}


@from_catalog(ENVIRONMENT, "channels")
def catalog_channel(tube: Tube, channel_id: str, record: Record, stamp: Stamp) -> Channel:
    """The channel as loaded now. The channel marked isSelf shows the self user's name and
    handle, as the original substitutes them."""
    catalog = tube.catalog
    is_self = bool(record.get("isSelf")) or channel_id == SELF_CHANNEL
    me = getattr(catalog, "self_user", None) or {}
    name, handle = str(record.get("name", "")), str(record.get("handle", ""))
    if is_self and me:
        name = str(me.get("name") or name)
        handle = f"@{me['username']}" if me.get("username") else handle
    start = float(whole(record.get("subscribers")))
    return read(
        Channel,
        record,
        id=channel_id,
        name=name,
        handle=handle,
        subscribers=growing(start, record.get("subscriberGrowth"), stamp.at),
        is_self=is_self,
        owner_id=str(record.get("ownerId") or (me.get("id", "") if is_self else "")),
    )


def _published_at(record: Record, stamp: Stamp) -> float:
    """A new upload is published when it arrives; a preloaded one `publishedAgo` before the
    run (or, for a record without it, an age cycling with its catalog order, as the original's
    labels do)."""
    if not stamp.preloaded:
        return stamp.at
    ago = record.get("publishedAgo")
    if ago is None:
        ago = (1 + (whole(record.get("order"), 1) * 5) % 27) * DAY
    return stamp.at - float(ago)


@from_catalog(ENVIRONMENT, "videos")
def catalog_video(tube: Tube, video_id: str, record: Record, stamp: Stamp) -> Video:
    category = str(record.get("category") or "")
    subject = str(record.get("thumbnailSubject") or SUBJECT_BY_CATEGORY.get(category, "abstract"))
    return read(
        Video,
        record,
        id=video_id,
        thumbnail_subject=subject,
        views=growing(float(whole(record.get("views"))), record.get("viewGrowth"), stamp.at),
        likes=growing(float(whole(record.get("likes"))), record.get("likeGrowth"), stamp.at),
        published_at=_published_at(record, stamp),
        arrived_at=float(stamp.at),
        uploaded=not stamp.preloaded,
    )


@from_catalog(ENVIRONMENT, "comments")
def catalog_comment(tube: Tube, comment_id: str, record: Record, stamp: Stamp) -> Comment:
    """A scenario comment; preloaded ones were written a few hours before the run."""
    catalog = tube.catalog
    user_id = str(record.get("user_id", ""))
    person = catalog.users.get(user_id) or {}
    me = getattr(catalog, "self_user", None) or {}
    return read(
        Comment,
        record,
        id=comment_id,
        user_id=user_id,
        author=str(person.get("name") or user_id or "Unknown viewer"),
        posted_at=stamp.at - (1 + stamp.order % 9) * HOUR if stamp.preloaded else stamp.at,
        by_self=bool(me) and user_id == me.get("id"),
    )


@from_catalog(ENVIRONMENT, "notifications")
def catalog_notification(
    tube: Tube, notification_id: str, record: Record, stamp: Stamp
) -> tuple[Notification, NotificationState]:
    """A notification and its state: a new one arrives unread; preloaded ones came in hours
    before the run, read as the catalog says."""
    arrived_at = stamp.at - (1 + stamp.order) * HOUR if stamp.preloaded else stamp.at
    channel = catalog_channel(tube, str(record.get("channel_id") or ""), stamp)
    notification = read(
        Notification,
        record,
        id=notification_id,
        arrived_at=float(arrived_at),
        channel_name=channel.name if channel else "",
    )
    return notification, NotificationState(read=stamp.preloaded and bool(record.get("isRead")))
