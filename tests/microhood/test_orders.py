"""Orders: market fills at the price of their moment, the original's two refusals, limit
orders that rest until the price reaches them, cancellation — and fills that replay exactly."""

from __future__ import annotations

import pytest

from apps.microhood import state as account
from apps.microhood.environment import MICROHOOD
from apps.microhood.orders import settle
from events.registry import ActionRejected, LoggedEvent
from tests.microhood.timeline import OUR_SCENARIOS, fold_until, scenario

SELL_TASK = scenario(OUR_SCENARIOS / "sell-order-absolute-active.json")  # MRDN jumps at 236.4


def act(hood, name: str, payload: dict, at: float, seq: int = 1000):
    """Perform at `at` as the server does (without a database): the state after, and the event
    as it would be logged (to replay it in a fold)."""
    performed = MICROHOOD.perform(hood, name, payload, at)
    return performed.state, LoggedEvent(seq, at, "action", name, performed.payload)


def order(symbol: str, side: str, quantity: int, **more) -> dict:
    return {"symbol": symbol, "side": side, "quantity": quantity, **more}


def test_a_market_buy_fills_at_the_rounded_price_of_its_moment_and_averages_the_cost():
    hood = fold_until(SELL_TASK, 100.0)
    quote = account.quote(hood, "MRDN", 100.0)
    held = hood.holding("MRDN")
    after, _ = act(hood, "place_order", order("MRDN", "buy", 2), at=100.0)
    filled = after.orders[-1]
    assert (filled.status, filled.price, filled.filled_at) == ("filled", quote, 100.0)
    assert after.buying_power == pytest.approx(hood.buying_power - 2 * quote)
    expected = round((held.shares * held.avg_cost + 2 * quote) / (held.shares + 2), 2)
    assert after.holding("MRDN") == account.Holding(held.shares + 2, expected)


def test_the_originals_refusals_name_the_reason():
    hood = fold_until(SELL_TASK, 10.0)
    with pytest.raises(ActionRejected, match="Insufficient buying power"):
        act(hood, "place_order", order("MRDN", "buy", 1000), at=10.0)
    with pytest.raises(ActionRejected, match="Not enough shares"):
        act(hood, "place_order", order("MRDN", "sell", 16), at=10.0)
    with pytest.raises(ActionRejected, match="at least 1"):
        act(hood, "place_order", order("MRDN", "buy", 0), at=10.0)
    with pytest.raises(ActionRejected) as unknown:
        act(hood, "place_order", order("NOPE", "buy", 1), at=10.0)
    assert unknown.value.status == 404


def test_a_sell_limit_above_the_market_rests_then_fills_when_the_price_reaches_it():
    hood = fold_until(SELL_TASK, 50.0)
    placed, _ = act(
        hood, "place_order", order("MRDN", "sell", 5, type="limit", limit_price=470.0), at=50.0
    )
    assert placed.orders[-1].status == "pending"
    assert account.shares_available(placed, "MRDN") == 10  # 15 held, 5 promised
    series = placed.prices["MRDN"]
    reach = series.first_reach(470.0, after=50.0, until=720.0, rising=True)
    assert settle(placed, reach - 1e-6).orders[-1].status == "pending"
    filled = settle(placed, reach + 1e-6).orders[-1]
    assert (filled.status, filled.price) == ("filled", 470.0)
    assert filled.filled_at == pytest.approx(reach)


def test_a_resting_buy_holds_back_buying_power_until_cancelled():
    hood = fold_until(SELL_TASK, 20.0)
    placed, event = act(
        hood, "place_order", order("CRGO", "buy", 10, type="limit", limit_price=30.0), at=20.0
    )
    assert placed.buying_power == pytest.approx(hood.buying_power - 300.0)
    assert account.portfolio_value(placed, 20.0) == pytest.approx(
        account.portfolio_value(hood, 20.0)
    )
    cancelled, _ = act(placed, "cancel_order", {"order_id": event.payload["id"]}, at=30.0, seq=1001)
    assert cancelled.buying_power == pytest.approx(hood.buying_power)
    assert cancelled.orders[-1].status == "cancelled"
    with pytest.raises(ActionRejected, match="already cancelled"):
        act(cancelled, "cancel_order", {"order_id": event.payload["id"]}, at=31.0, seq=1002)


def test_a_marketable_limit_fills_at_once_at_the_market_not_at_a_worse_limit():
    hood = fold_until(SELL_TASK, 10.0)
    quote = account.quote(hood, "MRDN", 10.0)
    after, _ = act(
        hood, "place_order", order("MRDN", "sell", 1, type="limit", limit_price=1.0), at=10.0
    )
    assert (after.orders[-1].status, after.orders[-1].price) == ("filled", quote)


def test_a_jump_fills_a_resting_sell_at_the_jump_and_replays_identically_from_the_log():
    """The limit is reached by the set_price at 236.4 (a step): filled then, at the better
    price. Folding the log from scratch at any later instant gives the same fill."""
    hood = fold_until(SELL_TASK, 200.0)
    _, event = act(
        hood, "place_order", order("MRDN", "sell", 5, type="limit", limit_price=478.0), at=200.0
    )
    later = fold_until(SELL_TASK, 300.0, actions=[event])
    fill = settle(later, 300.0).orders[-1]
    assert (fill.status, fill.filled_at, fill.price) == ("filled", 236.4, 481.35)
    again = settle(fold_until(SELL_TASK, 650.0, actions=[event]), 650.0).orders[-1]
    assert again == fill
