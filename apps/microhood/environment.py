"""MicroHood's registration with the core: scenario events, baselines, evaluation tables.

Scenario events (SentinelBench format, upstream-env-microhood.md §3):
- `preload_stocks {stock_symbols, watchlist_symbols, news_ids, buying_power, price_waypoints}`
  — the account the task starts from; `["*"]` = the whole catalog table. Each loaded symbol's
  price starts at its catalog price and ramps through `price_waypoints[symbol]` if given, else
  through our catalog's authored trace. Baselines are measured right after it.
- `new_news {news_id}` — a story arrives now.
- `set_price {symbol, price}` — a waypoint at the event's own time: the price jumps then.

Every reducer first settles resting limit orders up to the event's time (apps.microhood.orders),
so fills depend only on the log.
"""

from __future__ import annotations

import json
import sqlite3
from collections.abc import Mapping
from types import MappingProxyType
from typing import Annotated

from pydantic import Field

from apps.kit.legacy_tables import Table
from apps.kit.waypoints import Waypoints
from apps.microhood import state as account
from apps.microhood.actions import ACTIONS
from apps.microhood.bench import sample_pages
from apps.microhood.catalog import (
    listing,
    news_item,
    starting_price,
    stock_record,
    trace,
    watch_row,
)
from apps.microhood.orders import settle
from apps.microhood.state import (
    DEFAULT_BUYING_POWER,
    ENVIRONMENT,
    Holding,
    Hood,
    changed,
    empty_hood,
)
from events.registry import (
    Action,
    Environment,
    EventType,
    LoggedEvent,
    Measure,
    Reducer,
    timeless,
)
from events.schemas import Payload

# A waypoint as the original writes it: [time, price].
TimePrice = Annotated[list[float], Field(min_length=2, max_length=2)]


class PreloadStocks(Payload):
    stock_symbols: list[str] = Field(default_factory=list, description='["*"] = every stock')
    watchlist_symbols: list[str] = Field(default_factory=list, description='["*"] = all rows')
    news_ids: list[str] = Field(default_factory=list, description='["*"] = every story')
    buying_power: float = DEFAULT_BUYING_POWER
    price_waypoints: dict[str, list[TimePrice]] | None = Field(
        None, description="symbol → [[time, price], …] (overrides the catalog trace)"
    )


class NewNews(Payload):
    news_id: str = Field(description="catalog news id")


class SetPrice(Payload):
    symbol: str | None = None
    price: float | None = None


def load_stocks(hood: Hood, symbols: list[str], waypoints: Mapping) -> Hood:
    """Listings, holdings from the catalog, and each price series (skipping unknown symbols)."""
    stocks, prices, holdings = dict(hood.stocks), dict(hood.prices), dict(hood.holdings)
    for symbol in dict.fromkeys(symbols):
        record = stock_record(hood.catalog, symbol)
        if record is None:
            continue
        stocks[symbol] = listing(record)
        shares = record.get("shares") or 0
        holdings[symbol] = Holding(int(shares), float(record.get("avgCost") or 0.0))
        points = waypoints[symbol] if symbol in waypoints else trace(hood.catalog, symbol)
        prices[symbol] = Waypoints(starting_price(record)).with_points(points)
    return changed(hood, stocks=stocks, prices=prices, holdings=holdings)


def reduce_preload(hood: Hood, event: LoggedEvent) -> Hood:
    p, catalog = event.payload, hood.catalog
    waypoints = p.get("price_waypoints") or {}
    listed = catalog.expand(ENVIRONMENT, "stocks", p.get("stock_symbols"))
    hood = load_stocks(hood, listed, waypoints)
    # Waypoints for a symbol loaded earlier but not listed now still apply (the original's rule).
    prices = dict(hood.prices)
    for symbol, points in waypoints.items():
        if symbol in prices and symbol not in listed:
            prices[symbol] = prices[symbol].with_points(points)
    items, on = dict(hood.watch_items), dict(hood.watching)
    for symbol in catalog.expand(ENVIRONMENT, "watchlist", p.get("watchlist_symbols")):
        if symbol in catalog.table(ENVIRONMENT, "watchlist"):
            items[symbol] = MappingProxyType(watch_row(catalog, symbol))
            on[symbol] = True
    news = list(hood.news)
    for news_id in catalog.expand(ENVIRONMENT, "news", p.get("news_ids")):
        story = news_item(catalog, news_id, arrived_at=event.at, preloaded=True)
        if story is not None:
            news.append(story)
    hood = changed(
        hood,
        prices=prices,
        watch_items=items,
        watching=on,
        news=tuple(news),
        buying_power=float(p.get("buying_power", DEFAULT_BUYING_POWER)),
    )
    return changed(hood, opening_value=account.portfolio_value(hood, event.at))


def reduce_new_news(hood: Hood, event: LoggedEvent) -> Hood:
    news_id = event.payload["news_id"]
    if any(n.id == news_id for n in hood.news):
        return hood  # the same story delivered twice is shown once
    story = news_item(hood.catalog, news_id, arrived_at=event.at)
    return changed(hood, news=(*hood.news, story)) if story else hood


def reduce_set_price(hood: Hood, event: LoggedEvent) -> Hood:
    symbol, value = event.payload.get("symbol"), event.payload.get("price")
    if symbol is None or value is None or symbol not in hood.prices:
        return hood
    prices = {**hood.prices, symbol: hood.prices[symbol].with_point(event.at, value)}
    return changed(hood, prices=prices)


def settling(reduce: Reducer) -> Reducer:
    """`reduce`, after resting orders are settled up to the event's time."""
    return lambda hood, event: reduce(settle(hood, event.at), event)


EVENT_TYPES: Mapping[str, EventType] = MappingProxyType(
    {
        "preload_stocks": EventType(
            PreloadStocks,
            settling(reduce_preload),
            help="The account at the start: stocks, watchlist, news, buying power, price waypoints.",
            catalog_refs={
                "stock_symbols": "stocks",
                "watchlist_symbols": "watchlist",
                "news_ids": "news",
            },
            preload=True,
        ),
        "new_news": EventType(
            NewNews,
            settling(reduce_new_news),
            help="A news story arrives.",
            catalog_refs={"news_id": "news"},
        ),
        "set_price": EventType(
            SetPrice,
            settling(reduce_set_price),
            help="The price of a symbol jumps to `price` now (later waypoints ramp on from it).",
        ),
    }
)

SETTLED_ACTIONS: Mapping[str, Action] = MappingProxyType(
    {
        name: Action(
            action.schema,
            action.decide,
            settling(action.reduce),
            help=action.help,
            page=action.page,
            timed=action.timed,
        )
        for name, action in ACTIONS.items()
    }
)

# The original's metrics (eval_sql reads session_meta `baseline_<name>`), plus `news_count`,
# which the original's news scenario reads but its handler never captured.
BASELINES: Mapping[str, Measure] = MappingProxyType(
    {
        "portfolio_value": account.portfolio_value,
        "buying_power": timeless(lambda hood: hood.buying_power),
        "positions_value": account.positions_value,
        "order_count": timeless(lambda hood: len(account.filled_orders(hood))),
        "watchlist_count": timeless(lambda hood: len(account.watchlist_symbols(hood))),
        "mcro_price": account.mcro_price,
        "news_count": timeless(lambda hood: len(hood.news)),
    }
)


# --- evaluation tables (the original's names, columns and encodings) ---------------------------

STOCKS = Table("stocks", ("symbol TEXT", "name TEXT", "color TEXT", "avgCost REAL"))
STOCK_STATES = Table("stock_states", ("symbol TEXT", "shares INTEGER", "avgCost REAL"))
WATCHLIST = Table("watchlist", ("symbol TEXT", "data TEXT"))
WATCHLIST_STATES = Table("watchlist_states", ("symbol TEXT", "inWatchlist INTEGER"))
NEWS = Table("news", ("id TEXT", "data TEXT"))
ORDERS = Table(
    "orders",
    ("id TEXT", "symbol TEXT", "action TEXT", "quantity INTEGER", "price REAL", "type TEXT"),
)
CURRENT_PRICES = Table("current_prices", ("symbol TEXT", "price REAL"))


def materialize(hood: Hood, now: float, conn: sqlite3.Connection) -> None:
    """The account as of `now`: resting orders settled, prices at `now` unrounded. `orders`
    holds fills (the original had nothing else); `buying_power` joins session_meta."""
    hood = settle(hood, now)
    conn.execute(
        "INSERT OR REPLACE INTO session_meta (key, value) VALUES ('buying_power', ?)",
        (str(hood.buying_power),),
    )
    STOCKS.write(
        conn, ((s.symbol, s.name, s.color, s.catalog_avg_cost) for s in hood.stocks.values())
    )
    STOCK_STATES.write(conn, ((sym, h.shares, h.avg_cost) for sym, h in hood.holdings.items()))
    WATCHLIST.write(conn, ((sym, json.dumps(dict(row))) for sym, row in hood.watch_items.items()))
    WATCHLIST_STATES.write(conn, ((sym, hood.watching.get(sym, False)) for sym in hood.watch_items))
    NEWS.write(conn, ((n.id, n.data) for n in hood.news))
    ORDERS.write(
        conn,
        (
            (o.id, o.symbol, o.side, o.quantity, o.price, o.type)
            for o in account.filled_orders(hood)
        ),
    )
    CURRENT_PRICES.write(conn, ((sym, account.price(hood, sym, now)) for sym in hood.prices))


MICROHOOD = Environment(
    name=ENVIRONMENT,
    title="MicroHood",
    initial_state=empty_hood,
    event_types=EVENT_TYPES,
    actions=SETTLED_ACTIONS,
    baselines=BASELINES,
    materialize=materialize,
    urlconf="apps.microhood.urls",
    sample_pages=sample_pages,
)
