"""Filling orders: a market order at the price of its moment, a limit order when the price
reaches its limit — at the limit, or at the price after a jump if that is better (the original
filled every limit order at once at the limit: a sell limit far above the market minted cash).

The fill instant is a pure function of the price series, so fills are computed, not logged:
reducers and readers `settle` up to their moment, and replay fills the same orders alike."""

from __future__ import annotations

from dataclasses import replace

from apps.kit.state import with_items
from apps.microhood.state import Holding, Hood, Order, quote


def marketable(order_side: str, limit: float, market: float) -> bool:
    return market <= limit if order_side == "buy" else market >= limit


def fill_price(hood: Hood, order: Order, at: float) -> float:
    """What a fill at `at` pays: the market price, or for a limit order no worse than its limit."""
    market = quote(hood, order.symbol, at)
    if order.type != "limit" or order.limit_price is None:
        return market
    best = min if order.side == "buy" else max
    return round(best(market, order.limit_price), 2)


def with_fill(hood: Hood, order: Order, at: float, paid: float) -> Hood:
    """Apply a fill: shares and average cost move, cash moves (a resting buy's reserve is
    released). Buying power is whatever is left: the original's rules, no margin."""
    held = hood.holding(order.symbol)
    cash = hood.buying_power + order.reserved
    if order.side == "buy":
        shares = held.shares + order.quantity
        cost = held.shares * held.avg_cost + order.quantity * paid
        holding = Holding(shares, round(cost / shares, 2) if shares else 0.0)
        cash -= paid * order.quantity
    else:
        holding = Holding(held.shares - order.quantity, held.avg_cost)
        cash += paid * order.quantity
    filled = replace(order, status="filled", price=paid, filled_at=at)
    orders = tuple(filled if o.id == order.id else o for o in hood.orders)
    hood = replace(hood, buying_power=round(cash, 2), orders=orders)
    return with_items(hood, "holdings", [(order.symbol, holding)])


def next_fill(hood: Hood, until: float) -> tuple[float, Order] | None:
    """The resting order that fills first in (settled_to, until], and when."""
    first: tuple[float, Order] | None = None
    for order in hood.orders:
        if order.status != "pending" or order.symbol not in hood.prices:
            continue
        series = hood.prices[order.symbol]
        at = series.first_reach(
            order.limit_price,
            after=max(order.placed_at, hood.settled_to),
            until=until,
            rising=order.side == "sell",
        )
        if at is not None and (first is None or at < first[0]):
            first = (at, order)
    return first


def settle(hood: Hood, until: float) -> Hood:
    """Every resting order whose limit the price reaches by `until`, filled in time order."""
    if until <= hood.settled_to:
        return hood
    if not any(o.status == "pending" for o in hood.orders):
        return replace(hood, settled_to=until)
    while (found := next_fill(hood, until)) is not None:
        at, order = found
        hood = with_fill(hood, order, at, fill_price(hood, order, at))
    return replace(hood, settled_to=until)


def next_fill_time(hood: Hood, now: float, horizon: float) -> float | None:
    """When a resting order next fills after `now` (a page showing orders changes then)."""
    found = next_fill(replace(hood, settled_to=now), horizon)
    return found[0] if found else None
