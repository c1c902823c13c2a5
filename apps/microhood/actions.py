"""What an agent can do: place and cancel orders, put symbols on and off the watchlist (README:
"Agent actions"). The watchlist has explicit add/remove instead of the original's toggle, so a
repeated request cannot undo itself."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace
from types import MappingProxyType
from typing import Literal

from pydantic import Field

from apps.kit.deciding import checking, found, new_id
from apps.kit.fields import ItemId
from apps.kit.state import with_items
from apps.microhood import state as account
from apps.microhood.catalog import watch_row
from apps.microhood.orders import fill_price, marketable, settle, with_fill
from apps.microhood.state import ORDER_TYPES, SIDES, Hood, Order, Stock, WatchRow
from events.registry import Action, ActionRejected, LoggedEvent, PageStep
from events.schemas import Payload


class Symbol(Payload):
    symbol: ItemId = Field(description="a listed symbol, e.g. MRDN")


class PlaceOrder(Symbol):
    side: Literal[SIDES]
    quantity: int = Field(description="whole shares, at least 1")
    type: Literal[ORDER_TYPES] = "market"
    limit_price: float | None = Field(None, description="required for a limit order")


class CancelOrder(Payload):
    order_id: ItemId = Field(description="id of a resting limit order")


def listed(hood: Hood, symbol: str) -> Stock:
    return found(hood.stocks, symbol, "stock", "is listed")


def new_order(payload: Mapping, at: float) -> Order:
    return Order(
        id=str(payload["id"]),
        symbol=str(payload["symbol"]),
        side=str(payload["side"]),
        quantity=int(payload["quantity"]),
        type=str(payload.get("type") or "market"),
        limit_price=payload.get("limit_price"),
        placed_at=at,
        status="pending",
    )


def fills_now(hood: Hood, order: Order, at: float) -> bool:
    if order.type == "market" or order.limit_price is None:
        return True
    return marketable(order.side, order.limit_price, account.quote(hood, order.symbol, at))


def check_affordable(hood: Hood, order: Order, at: float) -> None:
    """The original's two refusals, for what the order fills at or holds back."""
    if order.side == "buy":
        each = fill_price(hood, order, at) if fills_now(hood, order, at) else order.limit_price
        if each * order.quantity > hood.buying_power + 1e-9:
            raise ActionRejected(
                f"Insufficient buying power: {order.quantity} × ${each:,.2f} is more than "
                f"${hood.buying_power:,.2f}"
            )
    elif order.quantity > account.shares_available(hood, order.symbol):
        raise ActionRejected(
            f"Not enough shares: you have {account.shares_available(hood, order.symbol)} "
            f"{order.symbol} to sell"
        )


def decide_place_order(hood: Hood, payload: dict, now: float) -> dict:
    hood = settle(hood, now)
    listed(hood, payload["symbol"])
    if payload["quantity"] < 1:
        raise ActionRejected("quantity must be a whole number of shares, at least 1")
    limit = payload.get("limit_price")
    if payload.get("type", "market") == "limit":
        if limit is None or limit <= 0:
            raise ActionRejected("limit_price must be a positive price for a limit order")
        payload["limit_price"] = round(float(limit), 2)
    else:
        payload["limit_price"] = None
    payload = {"id": new_id("ord"), **payload, "type": payload.get("type") or "market"}
    check_affordable(hood, new_order(payload, now), now)
    return payload


def reduce_place_order(hood: Hood, event: LoggedEvent) -> Hood:
    """A market (or marketable limit) order fills at its moment's price; a limit order rests,
    holding back buying power (a buy) — shares promised to a resting sell stay held."""
    order = new_order(event.payload, event.at)
    if order.symbol not in hood.stocks:
        return hood
    hood = replace(hood, orders=(*hood.orders, order))
    if fills_now(hood, order, event.at):
        return with_fill(hood, order, event.at, fill_price(hood, order, event.at))
    return replace(hood, buying_power=round(hood.buying_power - order.reserved, 2))


def resting(hood: Hood, order_id: str) -> Order:
    order = next((o for o in hood.orders if o.id == order_id), None)
    if order is None:
        raise ActionRejected(f"no order {order_id!r}", status=404)
    if order.status != "pending":
        raise ActionRejected(f"order {order_id} is already {order.status}", status=409)
    return order


def decide_cancel_order(hood: Hood, payload: dict, now: float) -> dict:
    resting(settle(hood, now), payload["order_id"])
    return payload


def reduce_cancel_order(hood: Hood, event: LoggedEvent) -> Hood:
    """The order stops resting; what it held back is buying power again."""
    order = next((o for o in hood.orders if o.id == event.payload["order_id"]), None)
    if order is None or order.status != "pending":
        return hood
    cancelled = replace(order, status="cancelled")
    orders = tuple(cancelled if o.id == order.id else o for o in hood.orders)
    return replace(hood, orders=orders, buying_power=round(hood.buying_power + order.reserved, 2))


decide_watch = checking("stocks", "symbol", "stock", "is listed")


def watching(on: bool, help: str) -> Action:
    """Putting the symbol on (or taking it off) the watchlist, by its star; the original keeps
    the stored row when it is taken off and flips the flag back when it is added again."""

    def reduce(hood: Hood, event: LoggedEvent) -> Hood:
        symbol = event.payload["symbol"]
        row = hood.watchlist.get(symbol)
        if row is None and on:
            data = watch_row(hood.catalog, symbol)
            row = None if data is None else WatchRow(symbol, MappingProxyType(data))
        if row is None:
            return hood
        return with_items(hood, "watchlist", [(symbol, replace(row, on=on))])

    return Action(Symbol, decide_watch, reduce, help=help, page=star_button)


# --- where a person does it (Action.page): forms marked data-action="<name>" ------------------


def stock_page(hood: Hood, payload: dict) -> PageStep:
    """The order ticket on the stock's page, filled in as typed."""
    form = {
        "side": payload["side"],
        "type": payload.get("type") or "market",
        "quantity": str(payload["quantity"]),
    }
    if payload.get("limit_price") is not None:
        form["limit_price"] = f"{payload['limit_price']:g}"
    return PageStep(f"stocks/{payload['symbol']}?side={payload['side']}", form)


def star_button(hood: Hood, payload: dict) -> PageStep:
    return PageStep(f"stocks/{payload['symbol']}", {})


def cancel_button(hood: Hood, payload: dict) -> PageStep:
    return PageStep("orders", {"order_id": payload["order_id"]})


ACTIONS: Mapping[str, Action] = MappingProxyType(
    {
        "place_order": Action(
            PlaceOrder,
            decide_place_order,
            reduce_place_order,
            help="Buy or sell whole shares at market, or with a limit price (rests until reached).",
            page=stock_page,
            timed=True,
        ),
        "cancel_order": Action(
            CancelOrder,
            decide_cancel_order,
            reduce_cancel_order,
            help="Cancel a resting limit order.",
            page=cancel_button,
            timed=True,
        ),
        "add_to_watchlist": watching(True, "Put a stock on the watchlist."),
        "remove_from_watchlist": watching(False, "Take a stock off the watchlist."),
    }
)
