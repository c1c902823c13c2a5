"""The screens' URL state, YouTube's own shapes: `watch?v=<id>`, `results?search_query=<q>`,
`playlist?list=<id>`, `channel/<id>?tab=about`. Canonical (defaults left out)."""

from __future__ import annotations

from dataclasses import dataclass

from apps.kit.query import InvalidQuery, QueryState, choice, item, text

__all__ = ["ChannelQuery", "InvalidQuery", "PlaylistQuery", "ResultsQuery", "WatchQuery"]

CHANNEL_TABS = ("videos", "playlists", "about")


@dataclass(frozen=True)
class WatchQuery(QueryState):
    v: str | None = item()


@dataclass(frozen=True)
class ResultsQuery(QueryState):
    search_query: str = text()


@dataclass(frozen=True)
class PlaylistQuery(QueryState):
    list: str | None = item()


@dataclass(frozen=True)
class ChannelQuery(QueryState):
    tab: str = choice(CHANNEL_TABS, default="videos", not_found=True)
