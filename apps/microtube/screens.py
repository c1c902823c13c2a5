"""What each MicroTube screen lists: pure functions of the state, memoised per state.

Counts and ages that move with the clock are not computed here (they depend on `now`); the
templates read them through the `microtube` tags, which also tell the page when they change.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from apps.kit.derived import per_state
from apps.kit.retractions import is_gone, present
from apps.microtube.state import (
    LIKED_VIDEOS,
    WATCH_LATER,
    Channel,
    Comment,
    Notification,
    Tube,
    Video,
)

RELATED_SHOWN = 10
SEARCH_FIELDS = ("title", "description")


@dataclass(frozen=True)
class Card:
    """One video as a feed shows it: the video and its channel (hashable, for fragments)."""

    video: Video
    channel: Channel | None

    @property
    def private(self) -> bool:
        """Made private by its uploader: a playlist shows it as "[Private video]"."""
        return is_gone(self.video)


@dataclass(frozen=True)
class PlaylistView:
    id: str
    name: str
    cards: tuple[Card, ...]  # private videos included: YouTube keeps their rows and counts them
    built_in: bool = False

    @property
    def cover(self) -> Video | None:
        """The thumbnail heading the playlist: its first video still public."""
        return next((c.video for c in self.cards if not c.private), None)


def _card(tube: Tube, video: Video) -> Card:
    return Card(video, tube.channels.get(video.channel_id))


def _cards(tube: Tube, videos: Sequence[Video]) -> tuple[Card, ...]:
    """The cards of `videos` still public: a video its uploader made private leaves the lists
    it was in (Home, Subscriptions, the channel, search, history), playlists aside."""
    return tuple(_card(tube, v) for v in present(videos))


@per_state()
def home(tube: Tube) -> tuple[Card, ...]:
    """Every video: uploads during the run first (the latest on top), then the preloaded ones in
    catalog order (the original's ordering)."""
    videos = list(tube.videos.values())
    uploads = [v for v in reversed(videos) if v.uploaded]  # arrival order, latest first
    return _cards(tube, uploads + [v for v in videos if not v.uploaded])


SHORTS_SHOWN = 8
SHELF_SHOWN = 5  # one row of Home's Shorts shelf


@per_state()
def home_videos(tube: Tube) -> tuple[Card, ...]:
    """Home's grid: the videos that are not shorts (those have their shelf). The original's
    catalog marks none, so there it is every video, as before."""
    return tuple(c for c in home(tube) if not c.video.is_short)


@per_state()
def home_shorts(tube: Tube) -> tuple[Card, ...]:
    """Home's Shorts shelf: the shorts, in Home order (none marked: no shelf)."""
    return tuple(c for c in home(tube) if c.video.is_short)[:SHELF_SHOWN]


@per_state()
def shorts(tube: Tube) -> tuple[Card, ...]:
    """The Shorts shelf: the videos marked as shorts, else (as the original, which ignored the
    flag) the first of the Home order."""
    marked = tuple(c for c in home(tube) if c.video.is_short)
    return (marked or home(tube))[:SHORTS_SHOWN]


def short_neighbours(tube: Tube, video_id: str) -> tuple[str | None, str | None]:
    """The previous and next short around `video_id` (up / down in the player)."""
    ids = [c.video.id for c in shorts(tube)]
    if video_id not in ids:
        return None, ids[0] if ids else None
    at = ids.index(video_id)
    return (ids[at - 1] if at else None), (ids[at + 1] if at + 1 < len(ids) else None)


@per_state()
def topics(tube: Tube) -> tuple[str, ...]:
    """The chips above Home: the categories of the videos on the site (each searches for it)."""
    seen = dict.fromkeys(v.category.title() for v in tube.videos.values() if v.category)
    return tuple(seen)[:12]


@per_state()
def subscribed_channels(tube: Tube) -> tuple[Channel, ...]:
    return tuple(c for cid, c in tube.channels.items() if tube.is_subscribed(cid))


@per_state()
def subscriptions(tube: Tube) -> tuple[Card, ...]:
    """Videos of subscribed channels, most recently published first."""
    videos = [v for v in tube.videos.values() if tube.is_subscribed(v.channel_id)]
    return _cards(tube, sorted(videos, key=lambda v: -v.published_at))


@per_state()
def history(tube: Tube) -> tuple[Card, ...]:
    """Watched videos, the latest first."""
    return _cards(tube, [tube.videos[v] for v in reversed(tube.watched) if v in tube.videos])


@per_state()
def search(tube: Tube, query: str) -> tuple[Card, ...]:
    """Case-insensitive substring over title, description and channel name (the server-side
    search of the original, which also covers descriptions)."""
    needle = query.strip().casefold()
    if not needle:
        return ()
    found = []
    for card in home(tube):
        texts = [getattr(card.video, f) for f in SEARCH_FIELDS]
        if card.channel is not None:
            texts += [card.channel.name, card.channel.handle]
        if any(needle in text.casefold() for text in texts):
            found.append(card)
    return tuple(found)


@per_state()
def channel_videos(tube: Tube, channel_id: str) -> tuple[Card, ...]:
    videos = [v for v in tube.videos.values() if v.channel_id == channel_id]
    return _cards(tube, sorted(videos, key=lambda v: -v.published_at))


@per_state()
def related(tube: Tube, video_id: str) -> tuple[Card, ...]:
    return tuple(c for c in home(tube) if c.video.id != video_id)[:RELATED_SHOWN]


@per_state()
def comments(tube: Tube, video_id: str) -> tuple[Comment, ...]:
    """The user's own comments first (newest on top, as YouTube pins them for their author),
    then everyone's, newest first."""
    mine = [c for c in tube.user_comments.values() if c.video_id == video_id]
    theirs = [c for c in tube.comments.values() if c.video_id == video_id]
    newest = lambda c: -c.posted_at  # noqa: E731
    return tuple(sorted(mine, key=newest)) + tuple(sorted(theirs, key=newest))


@dataclass(frozen=True)
class NotificationRow:
    notification: Notification
    channel: Channel | None
    channel_name: str
    video: Video | None
    read: bool


@per_state()
def notifications(tube: Tube) -> tuple[NotificationRow, ...]:
    """Not dismissed, newest first."""
    rows = []
    for nid, n in tube.notifications.items():
        state = tube.notification_states[nid]
        if state.dismissed:
            continue
        channel = tube.channels.get(n.channel_id)
        rows.append(
            NotificationRow(
                notification=n,
                channel=channel,
                channel_name=channel.name if channel else n.channel_name or "MicroTube",
                video=tube.videos.get(n.video_id),
                read=state.read,
            )
        )
    return tuple(sorted(rows, key=lambda r: -r.notification.arrived_at))


def notification_target(tube: Tube, notification_id: str) -> str:
    """Where opening a notification goes (a path under the environment root): its video when
    the site has it, else its channel, else the feed. (The original guessed a video from the
    message's first word.)"""
    n = tube.notifications[notification_id]
    if n.video_id in tube.videos:
        return f"watch?v={n.video_id}"
    if n.channel_id in tube.channels:
        return f"channel/{n.channel_id}"
    return ""


def _playlist_cards(tube: Tube, videos: Sequence[Video]) -> tuple[Card, ...]:
    """A playlist's cards: unlike every other list, a playlist keeps the row of a video made
    private since, as YouTube does ("[Private video]", counted in the playlist's videos)."""
    return tuple(_card(tube, v) for v in videos)


def marked(tube: Tube, flag: str) -> tuple[Card, ...]:
    """The videos whose state has `flag` set (liked, saved for later), in arrival order."""
    flagged = [tube.videos[v] for v, s in tube.video_states.items() if getattr(s, flag)]
    return _playlist_cards(tube, flagged)


@per_state()
def playlists(tube: Tube) -> tuple[PlaylistView, ...]:
    """Watch later and Liked videos, then the user's playlists, oldest first."""
    built_in = (
        PlaylistView(WATCH_LATER, "Watch later", marked(tube, "saved"), built_in=True),
        PlaylistView(LIKED_VIDEOS, "Liked videos", marked(tube, "liked"), built_in=True),
    )
    own = tuple(
        PlaylistView(
            p.id,
            p.name,
            _playlist_cards(tube, [tube.videos[v] for v in p.video_ids if v in tube.videos]),
        )
        for p in tube.playlists.values()
    )
    return built_in + own


def playlist(tube: Tube, playlist_id: str) -> PlaylistView | None:
    return next((p for p in playlists(tube) if p.id == playlist_id), None)
