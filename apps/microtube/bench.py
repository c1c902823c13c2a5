"""The MicroTube pages worth timing (`manage.py bench_pages --env microtube`), from the state:
every feed, a search, a channel, a playlist, Shorts and the watch page of the newest video. Paths are
relative to the environment root (`/r/<token>/microtube/`); opening a watch page records a
watch, as it does for a person."""

from __future__ import annotations

from apps.microtube import screens
from apps.microtube.query import ChannelQuery, ResultsQuery, WatchQuery
from apps.microtube.state import WATCH_LATER, Tube


def sample_pages(tube: Tube) -> list[str]:
    pages = [
        "",
        "feed/subscriptions",
        "feed/history",
        "feed/you",
        "feed/playlists",
        f"playlist?list={WATCH_LATER}",
        "notifications",
        "shorts",
        "results" + ResultsQuery(search_query="how").querystring(),
    ]
    cards = screens.home(tube)
    if cards:
        newest = cards[0].video
        pages += [
            "watch" + WatchQuery(v=newest.id).querystring(),
            f"shorts/{newest.id}",
            f"channel/{newest.channel_id}",
            f"channel/{newest.channel_id}" + ChannelQuery(tab="about").querystring(),
        ]
    return pages
