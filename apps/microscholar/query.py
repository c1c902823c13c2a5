"""The screens' URL state: every screen a stable, canonical URL (apps.kit.query).

- search: `?q=agents&as_ylo=2024&as_yhi=2025&sort=date&start=10` (Google Scholar's names for the
  year range and the offset); no `q` is the home page with recommended articles.
- a scholar's profile: `citations?user=<id>&sortby=pubdate`.
- alerts: `alerts?filter=unread`.
"""

from __future__ import annotations

from dataclasses import dataclass

from apps.kit.query import InvalidQuery, QueryState, choice, text

SORTS = ("relevance", "date")
PROFILE_SORTS = ("cited", "pubdate")
ALERT_FILTERS = ("all", "unread")
PER_PAGE = 10


def whole_number(name: str, value: str) -> int | None:
    """`value` of parameter `name` as a non-negative integer (None when empty)."""
    if not value:
        return None
    if not value.isdigit():
        raise InvalidQuery(f"{name}={value!r} is not valid; expected a whole number")
    return int(value)


@dataclass(frozen=True)
class SearchQuery(QueryState):
    q: str = text()
    as_ylo: str = text(max_length=4)
    as_yhi: str = text(max_length=4)
    sort: str = choice(SORTS, default="relevance")
    start: str = text(max_length=6)

    def check(self) -> SearchQuery:
        """Raise InvalidQuery naming a parameter that is not a number."""
        for name in ("as_ylo", "as_yhi", "start"):
            whole_number(name, getattr(self, name))
        return self

    @property
    def since(self) -> int | None:
        return whole_number("as_ylo", self.as_ylo)

    @property
    def until(self) -> int | None:
        return whole_number("as_yhi", self.as_yhi)

    @property
    def offset(self) -> int:
        return whole_number("start", self.start) or 0


@dataclass(frozen=True)
class ProfileQuery(QueryState):
    user: str = text(max_length=80)
    sortby: str = choice(PROFILE_SORTS, default="cited")


@dataclass(frozen=True)
class AlertsQuery(QueryState):
    filter: str = choice(ALERT_FILTERS, default="all")
