"""The screens' URL state: the feed's length, searches and the profile tab live in the query.

`/r/<token>/microgram/?page=2`, `explore/?q=sunset`, `profile/<id>/?tab=saved` — every screen is
a stable, shareable URL, canonical (defaults left out).
"""

from __future__ import annotations

from dataclasses import dataclass

from apps.kit.query import QueryState, choice, text

FEED_PAGE_SIZE = 10  # posts per "Load more", as the original
FEED_PAGES = tuple(str(n) for n in range(1, 31))  # up to the whole 300-post catalog


@dataclass(frozen=True)
class FeedQuery(QueryState):
    page: str = choice(FEED_PAGES, default="1")

    @property
    def shown(self) -> int:
        return int(self.page) * FEED_PAGE_SIZE


@dataclass(frozen=True)
class SearchQuery(QueryState):
    """What Explore's grid and Search's people are filtered by."""

    q: str = text()


@dataclass(frozen=True)
class ProfileQuery(QueryState):
    tab: str = choice(("posts", "saved", "tagged"), default="posts", not_found=True)
