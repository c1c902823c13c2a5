"""MicroFy's URL state: the mood highlighted on home and the search text.

`/r/<token>/microfy/?mood=<id>` and `/r/<token>/microfy/search?q=<text>`: every screen is a
stable URL (tracks, artists and playlists have paths of their own, see urls.py).
"""

from __future__ import annotations

from dataclasses import dataclass

from apps.kit.query import InvalidQuery, QueryState, item, text

__all__ = ["HomeQuery", "InvalidQuery", "SearchQuery"]


@dataclass(frozen=True)
class HomeQuery(QueryState):
    mood: str | None = item()


@dataclass(frozen=True)
class SearchQuery(QueryState):
    q: str = text()
