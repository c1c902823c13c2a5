"""MicroHood's registration with the core: scenario events, baselines, evaluation tables (the
README's "Scenario events" and "Evaluation tables"). Every reducer first settles resting limit
orders up to the event's time (apps.microhood.orders), so fills depend only on the log."""

from __future__ import annotations

import json
import sqlite3
from collections.abc import Mapping
from dataclasses import replace
from types import MappingProxyType
from typing import Annotated, Any

from pydantic import Field

from apps.kit.arrivals import Delivery, Stamp, arrival, event_types, preload
from apps.kit.counts import ShownCount, item_on_screen
from apps.kit.environments import declare
from apps.kit.state import with_items
from apps.kit.tables import KEY, VALUE, Table, named, tables
from apps.kit.waypoints import Waypoints
from apps.microhood import state as account
from apps.microhood.actions import ACTIONS as ORDER_ACTIONS
from apps.microhood.catalog import listing, news_item, starting_price, stock_record, trace
from apps.microhood.orders import settle
from apps.microhood.state import DEFAULT_BUYING_POWER, ENVIRONMENT, Holding, Hood, Stock, WatchRow
from events.registry import EventType, LoggedEvent, Reducer, counted
from events.schemas import Payload


def make_listing(hood: Hood, symbol: str, stamp: Stamp) -> tuple[Stock, Holding] | None:
    """A listing and the position the catalog gives it (its prices come in `open_account`)."""
    record = stock_record(hood.catalog, symbol)
    if record is None:
        return None
    return listing(record), Holding(
        int(record.get("shares") or 0), float(record.get("avgCost") or 0.0)
    )


def make_watch_row(hood: Hood, symbol: str, stamp: Stamp) -> WatchRow | None:
    row = hood.catalog.table(ENVIRONMENT, "watchlist").get(symbol)
    return None if row is None else WatchRow(symbol, MappingProxyType(dict(row)))


deliver_news = Delivery("news", news_item)

# A waypoint as the original writes it: [time, price].
TimePrice = Annotated[list[float], Field(min_length=2, max_length=2)]


class AccountFields(Payload):
    buying_power: float = DEFAULT_BUYING_POWER
    price_waypoints: dict[str, list[TimePrice]] | None = Field(
        None, description="symbol → [[time, price], …] (overrides the catalog trace)"
    )


def open_account(hood: Hood, payload: Mapping[str, Any], at: float) -> Hood:
    """Once the listings, watchlist and news are in: each new listing's price series (from its
    catalog price through the scenario's waypoints, else our catalog's trace), the buying power
    and the opening value ("Today" is measured from it)."""
    waypoints = payload.get("price_waypoints") or {}
    prices = {}
    for symbol in hood.stocks:
        if symbol not in hood.prices:
            points = waypoints[symbol] if symbol in waypoints else trace(hood.catalog, symbol)
            start = starting_price(stock_record(hood.catalog, symbol))
            prices[symbol] = Waypoints(start).with_points(points)
        elif symbol in waypoints:  # listed before: its waypoints still apply (the original's rule)
            prices[symbol] = hood.prices[symbol].with_points(waypoints[symbol])
    buying_power = float(payload.get("buying_power", DEFAULT_BUYING_POWER))
    hood = replace(with_items(hood, "prices", prices.items()), buying_power=buying_power)
    return replace(hood, opening_value=account.portfolio_value(hood, at))


class SetPrice(Payload):
    symbol: str | None = None
    price: float | None = None


def reduce_set_price(hood: Hood, event: LoggedEvent) -> Hood:
    symbol, value = event.payload.get("symbol"), event.payload.get("price")
    if symbol is None or value is None or symbol not in hood.prices:
        return hood
    return with_items(hood, "prices", [(symbol, hood.prices[symbol].with_point(event.at, value))])


def settled_first(reduce: Reducer[Hood]) -> Reducer[Hood]:
    """`reduce`, after resting orders are settled up to the event's time."""
    return lambda hood, event: reduce(settle(hood, event.at), event)


DECLARED = event_types(
    preload(
        "preload_stocks",
        {
            "stock_symbols": ("stocks", Delivery("stocks", make_listing, states="holdings")),
            "watchlist_symbols": ("watchlist", Delivery("watchlist", make_watch_row)),
            "news_ids": ("news", deliver_news),
        },
        base=AccountFields,
        then=open_account,
        environment=ENVIRONMENT,
        help="The account at the start: stocks, watchlist, news, buying power, price waypoints.",
    ),
    arrival(
        "new_news",
        "news_id",
        "news",
        deliver_news,
        help="A news story arrives.",
        description="catalog news id",
    ),
    (
        "set_price",
        EventType(
            SetPrice,
            reduce_set_price,
            help="The price of a symbol jumps to `price` now (later waypoints ramp on from it).",
        ),
    ),
)

# Every event and action first settles the orders resting until its moment.
EVENT_TYPES, ACTIONS = (
    MappingProxyType({name: replace(e, reduce=settled_first(e.reduce)) for name, e in d.items()})
    for d in (DECLARED, ORDER_ACTIONS)
)

# The original's metrics (eval_sql reads session_meta `baseline_<name>`), plus `news_count`,
# which the original's news scenario reads but its handler never captured. Three move with the
# clock (they are read at the preload's moment); the others are counts of the state.
BASELINES = MappingProxyType(
    {
        "portfolio_value": account.portfolio_value,
        "positions_value": account.positions_value,
        "mcro_price": account.mcro_price,
        **counted(
            {
                "buying_power": lambda hood: hood.buying_power,
                "order_count": lambda hood: len(account.filled_orders(hood)),
                "watchlist_count": lambda hood: len(account.watchlist_symbols(hood)),
                "news_count": lambda hood: len(hood.news),
            }
        ),
    }
)


# --- evaluation tables (the original's names, columns and encodings) ---------------------------

write_tables = tables(
    Table.items(
        "stocks",
        {**named("symbol TEXT", "name TEXT", "color TEXT"), "avgCost REAL": "catalog_avg_cost"},
    ),
    Table.keyed(
        "stock_states",
        "holdings",
        {"symbol TEXT": KEY, "shares INTEGER": "shares", "avgCost REAL": "avg_cost"},
    ),
    Table.items(
        "watchlist", {"symbol TEXT": "symbol", "data TEXT": lambda row: json.dumps(dict(row.data))}
    ),
    Table.items(
        "watchlist_states", {"symbol TEXT": "symbol", "inWatchlist INTEGER": "on"}, "watchlist"
    ),
    Table.items("news", {**named("id TEXT", "data TEXT"), "publishedAt REAL": "published_at"}),
    # Fills only: the original had no other orders.
    Table(
        "orders",
        lambda hood, now: account.filled_orders(hood),
        {
            **named("id TEXT", "symbol TEXT"),
            "action TEXT": "side",
            **named("quantity INTEGER", "price REAL", "type TEXT"),
            # Ours: when it filled, so eval_sql can ask for a fill inside a price's window.
            "filledAt REAL": "filled_at",
        },
    ),
    # The price at `now`, unrounded.
    Table.keyed(
        "current_prices",
        lambda hood, now: {s: account.price(hood, s, now) for s in hood.prices},
        {"symbol TEXT": KEY, "price REAL": VALUE},
    ),
)


def materialize(hood: Hood, now: float, conn: sqlite3.Connection) -> None:
    """The account as of `now`, resting orders settled; `buying_power` joins session_meta."""
    hood = settle(hood, now)
    conn.execute(
        "INSERT OR REPLACE INTO session_meta (key, value) VALUES ('buying_power', ?)",
        (str(hood.buying_power),),
    )
    write_tables(hood, now, conn)


# The numbers shown in more than one place (apps.kit.counts): a position's shares in the home
# page's list and on its stock page; the buying power on the home page and the trade ticket.
SHOWN_COUNTS = (
    ShownCount(
        "shares of the stock on screen",
        lambda hood, now: 0,
        ("Your position Shares {n}",),
        value_on=lambda hood, now, path: hood.holding(item_on_screen(path, "stocks/")).shares,
    ),
    ShownCount(
        "shares listed",
        lambda hood, now: 0,
        (r"\b{key} {n} shares?",),
        value_of=lambda hood, now, symbol: hood.holding(symbol).shares,
    ),
    ShownCount("buying power", lambda hood, now: int(hood.buying_power), (r"Buying power \${n}",)),
)


MICROHOOD = declare(__name__, title="MicroHood", initial_state=Hood.of)
