"""MicroHood prices against the price model written independently from the reference
(upstream-env-microhood.md §3), on real timelines, at many instants and at the exact instants
where the scenarios' thresholds are crossed.

The reference model below is written from the text only: starting price = catalog
currentPrice; bulk `price_waypoints` (and, on our catalog, the authored trace when the preload
sets none for the symbol) inserted at preload; a `set_price` inserted only when it fires;
insertion seeds (0, start) into an empty list for a time > 0 and goes after equal times; the
price is flat before the first and after the last point, linear in between (right bisect).
"""

from __future__ import annotations

import json
import sqlite3
from pathlib import Path

import pytest

from apps.microhood import state as account
from apps.microhood.environment import MICROHOOD
from events.catalog import load_catalog
from events.evaluation import GradingSnapshot
from tests.environments.cases import UPSTREAM_SCENARIOS, copy_upstream_catalog
from tests.microhood.timeline import OUR_CATALOG, OUR_SCENARIOS, fold_until, scenario


def reference_points(start: float, inserts: list[tuple[float, float]]) -> list[list[float]]:
    points: list[list[float]] = []
    for at, value in inserts:
        if not points and at > 0:
            points.append([0.0, start])
        i = 0
        while i < len(points) and points[i][0] <= at:
            i += 1
        points.insert(i, [at, value])
    return points


def reference_price(points: list[list[float]], start: float, now: float) -> float:
    if not points:
        return start
    if now <= points[0][0]:
        return points[0][1]
    if now >= points[-1][0]:
        return points[-1][1]
    i = max(k for k, p in enumerate(points) if p[0] <= now)
    (t0, p0), (t1, p1) = points[i], points[i + 1]
    return p0 + (p1 - p0) * (now - t0) / (t1 - t0)


class Reference:
    """The reference model of one scenario: per symbol, the points known at `now`."""

    def __init__(self, data: dict, catalog_dir: Path, traces: dict):
        self.data = data
        rows = (catalog_dir / "microhood" / "stocks.jsonl").read_text().splitlines()
        self.start = {
            r["symbol"]: float(r["currentPrice"]) for r in map(json.loads, filter(None, rows))
        }
        self.traces = traces

    def price(self, symbol: str, now: float) -> float:
        start = self.start[symbol]
        inserts: list[tuple[float, float]] = []
        for event in sorted(self.data["events"], key=lambda e: e["time"]):
            if event["time"] > now:
                break
            payload = event["payload"]
            if event["type"] == "preload_stocks":
                bulk = (payload.get("price_waypoints") or {}).get(symbol)
                if bulk is None:
                    bulk = self.traces.get(symbol, [])
                inserts = [(float(t), float(p)) for t, p in bulk]
            elif event["type"] == "set_price" and payload.get("symbol") == symbol:
                inserts.append((float(event["time"]), float(payload["price"])))
        return reference_price(reference_points(start, inserts), start, now)

    def crossing(self, symbol: str, level: float, rising: bool) -> float:
        """The first instant the reference price is at/above (at/below) `level`: a jump's own
        time, or the exact solution on a ramp (bisection on the reference model)."""
        lo, hi = 0.0, 720.0
        reached = (lambda v: v >= level) if rising else (lambda v: v <= level)
        for _ in range(200):
            mid = (lo + hi) / 2
            # the first crossing: search the earliest point that reaches on [0, mid]
            if any(reached(self.price(symbol, t)) for t in _grid(0.0, mid)):
                hi = mid
            else:
                lo = mid
        return hi


def _grid(a: float, b: float, n: int = 64) -> list[float]:
    return [a + (b - a) * k / n for k in range(n + 1)]


def our_traces() -> dict:
    return json.loads((OUR_CATALOG / "microhood" / "price_traces.json").read_text())


INSTANTS = [
    0.0,
    0.5,
    10.0,
    59.99,
    60.0,
    60.01,
    100.52,
    141.36,
    141.37,
    226.68,
    300.0,
    348.67,
    409.93,
    433.62,
    457.08,
    599.5,
    630.0,
    719.99,
    720.0,
    900.0,
]


@pytest.mark.parametrize("path", sorted(OUR_SCENARIOS.glob("*.json")), ids=lambda p: p.stem)
def test_our_scenarios_price_every_symbol_as_the_reference_does(path):
    data = scenario(path)
    reference = Reference(data, OUR_CATALOG, our_traces())
    for now in INSTANTS:
        hood = fold_until(data, now)
        for symbol in hood.prices:
            assert account.price(hood, symbol, now) == pytest.approx(
                reference.price(symbol, now), abs=1e-9
            ), (symbol, now)


def upstream_cases() -> list[Path]:
    return sorted(p for p in UPSTREAM_SCENARIOS.glob("microhood/*.json") if p.name != "dev.json")


@pytest.fixture(scope="module")
def upstream_catalog(tmp_path_factory):
    return copy_upstream_catalog("microhood", tmp_path_factory.mktemp("hood-upstream"))


@pytest.mark.upstream
@pytest.mark.parametrize("path", upstream_cases(), ids=lambda p: p.stem)
def test_the_originals_scenarios_price_as_the_reference_on_its_catalog(path, upstream_catalog):
    data = scenario(path)
    catalog = load_catalog(upstream_catalog)
    reference = Reference(data, upstream_catalog, traces={})  # the original reads no traces
    for now in INSTANTS:
        hood = fold_until(data, now, catalog)
        for symbol in hood.prices:
            assert account.price(hood, symbol, now) == pytest.approx(
                reference.price(symbol, now), abs=1e-9
            ), (symbol, now)


def price_eval(hood, now: float, sql: str):
    conn = sqlite3.connect(":memory:")
    GradingSnapshot(MICROHOOD, hood, {}, now, 1.0, 720.0).write(conn)
    return conn.execute(sql).fetchone()[0]


# (scenario file, symbol, threshold, rising): price conditions of ours and the original's.
OUR_THRESHOLDS = [
    ("price-absolute-passive", "BRKW", 520.0, True),
    ("orders-absolute-active", "CRGO", 42.2, True),
    ("sell-order-absolute-active", "MRDN", 480.0, True),
    ("buy-dip-relative-active", "VNTA", 219.15, False),
    ("rebalance-relative-active", "HLXB", 105.11, True),
]
UPSTREAM_THRESHOLDS = [
    ("price-absolute-passive", "CHIP", 520.0, True),
    ("orders-absolute-active", "DRNE", 42.2, True),
    ("sell-order-absolute-active", "MCRO", 480.0, True),
    ("buy-dip-relative-active", "VOLT", 223.58, False),
    ("rebalance-relative-active", "NEOS", 106.15, True),
]
JUST = 1e-6


def check_crossing(data, reference, catalog, symbol, level, rising):
    crossing = reference.crossing(symbol, level, rising)
    before, after = (
        fold_until(data, crossing - JUST, catalog),
        fold_until(data, crossing + JUST, catalog),
    )
    sql = f"SELECT price FROM current_prices WHERE symbol='{symbol}'"
    below, above = price_eval(before, crossing - JUST, sql), price_eval(after, crossing + JUST, sql)
    reached = (lambda v: v >= level) if rising else (lambda v: v <= level)
    assert not reached(below) and reached(above), (crossing, below, above)
    return crossing


@pytest.mark.parametrize(
    "name,symbol,level,rising", OUR_THRESHOLDS, ids=[t[0] for t in OUR_THRESHOLDS]
)
def test_our_thresholds_are_crossed_at_the_reference_instant_which_is_condition_at(
    name, symbol, level, rising
):
    data = scenario(OUR_SCENARIOS / f"{name}.json")
    crossing = check_crossing(
        data, Reference(data, OUR_CATALOG, our_traces()), None, symbol, level, rising
    )
    assert crossing == pytest.approx(data["condition_at"], abs=1e-6)


@pytest.mark.upstream
@pytest.mark.parametrize(
    "name,symbol,level,rising", UPSTREAM_THRESHOLDS, ids=[t[0] for t in UPSTREAM_THRESHOLDS]
)
def test_the_originals_thresholds_are_crossed_at_the_reference_instant(
    name, symbol, level, rising, upstream_catalog
):
    data = scenario(UPSTREAM_SCENARIOS / "microhood" / f"{name}.json")
    reference = Reference(data, upstream_catalog, traces={})
    check_crossing(data, reference, load_catalog(upstream_catalog), symbol, level, rising)


@pytest.mark.parametrize("name", ["portfolio-absolute-passive", "portfolio-relative-passive"])
def test_the_portfolio_tasks_hold_from_condition_at_on_the_reference_prices_and_ours(name):
    """Portfolio = buying power + Σ shares × price (every holding moving): the scenario's own
    eval_sql on our tables and the reference total agree on both sides of condition_at."""
    data = scenario(OUR_SCENARIOS / f"{name}.json")
    reference = Reference(data, OUR_CATALOG, our_traces())
    rows = map(
        json.loads,
        filter(None, (OUR_CATALOG / "microhood" / "stocks.jsonl").read_text().splitlines()),
    )
    shares = {r["symbol"]: r["shares"] for r in rows}

    def total(now: float) -> float:
        return 10_000.0 + sum(n * reference.price(s, now) for s, n in shares.items() if n)

    start = total(0.0)
    for now, holds in ((data["condition_at"] - 0.01, False), (data["condition_at"], True)):
        hood = fold_until(data, now)
        conn = sqlite3.connect(":memory:")
        baselines = MICROHOOD.measure_baselines(fold_until(data, 0.0), 0.0)
        GradingSnapshot(MICROHOOD, hood, baselines, now, 1.0, 720.0).write(conn)
        assert bool(conn.execute(data["eval_sql"]).fetchone()[0]) is holds
        assert account.portfolio_value(hood, now) == pytest.approx(total(now), abs=1e-6)
    assert baselines["portfolio_value"] == pytest.approx(start, abs=1e-6)
