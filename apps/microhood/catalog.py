"""Catalog records (SentinelBench format) → listings, news items, watchlist rows, and our
authored price traces (`price_traces.json`: symbol → [[time, price], …]; README: "Prices")."""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

from apps.kit.arrivals import Stamp
from apps.kit.feeds import from_catalog
from apps.kit.records import Record, read
from apps.microhood.state import ENVIRONMENT, Hood, NewsItem, Stock

TRACES = "price_traces"


def _number(value: Any) -> float | None:
    return float(value) if isinstance(value, int | float) and not isinstance(value, bool) else None


def listing(record: Mapping[str, Any]) -> Stock:
    return read(
        Stock,
        record,
        symbol=str(record["symbol"]),
        name=str(record.get("name") or record["symbol"]),
        catalog_avg_cost=_number(record.get("avgCost")) or 0.0,
        market_cap=_number(record.get("marketCap")),
        pe_ratio=_number(record.get("peRatio")),
        dividend_yield=_number(record.get("dividendYield")),
    )


def stock_record(catalog: Any, symbol: str) -> Mapping[str, Any] | None:
    return catalog.table(ENVIRONMENT, "stocks").get(symbol)


def starting_price(record: Mapping[str, Any]) -> float:
    return _number(record.get("currentPrice")) or 0.0


def trace(catalog: Any, symbol: str) -> list[tuple[float, float]]:
    """Our catalog's authored waypoints for `symbol` ([] without a trace document)."""
    traces = catalog.documents.get(ENVIRONMENT, {}).get(TRACES) or {}
    points = traces.get(symbol) if isinstance(traces, dict) else None
    return [(float(t), float(p)) for t, p in points or ()]


@from_catalog(ENVIRONMENT, "news")
def news_item(hood: Hood, news_id: str, record: Record, stamp: Stamp) -> NewsItem:
    """The catalog story; a preloaded one is dated `ageMinutes` before its arrival, one that
    arrives during the task is dated then."""
    age = (_number(record.get("ageMinutes")) or 0.0) * 60 if stamp.preloaded else 0.0
    data = json.dumps(dict(record))
    return read(NewsItem, record, id=news_id, published_at=stamp.at - age, data=data)


def watch_row(catalog: Any, symbol: str) -> Mapping[str, Any] | None:
    """The catalog's watchlist row, or one built from the listing (the original's toggle)."""
    row = catalog.table(ENVIRONMENT, "watchlist").get(symbol)
    if row is not None:
        return dict(row)
    record = stock_record(catalog, symbol)
    if record is None:
        return None
    return {
        "symbol": symbol,
        "name": record.get("name"),
        "price": record.get("currentPrice"),
        "change": record.get("change"),
        "changePercent": record.get("changePercent"),
    }
