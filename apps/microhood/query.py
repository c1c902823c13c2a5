"""The screens' URL state: chart range, order side, search text — canonical query strings."""

from __future__ import annotations

from dataclasses import dataclass

from apps.kit.query import InvalidQuery, QueryState, choice, text
from apps.microhood.state import SIDES

__all__ = ["RANGES", "ChartQuery", "InvalidQuery", "SearchQuery", "StockQuery"]

RANGES = ("1D", "1W", "1M", "3M", "YTD", "1Y", "ALL")


@dataclass(frozen=True)
class ChartQuery(QueryState):
    range: str = choice(RANGES, default="1D")


@dataclass(frozen=True)
class StockQuery(QueryState):
    range: str = choice(RANGES, default="1D")
    side: str = choice(SIDES, default="buy")


@dataclass(frozen=True)
class SearchQuery(QueryState):
    q: str = text()
