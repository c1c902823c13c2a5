"""Line charts as SVG paths: a value over the simulated session, or a longer made-up history
(first drawn for MicroHood's price and portfolio charts; any value over time can use them).

The 1D line is the real thing from the preload on — the value at sampled simulated instants up
to `now`, ending exactly at the value of `now` — and it grows across the session's width as time
passes. Before it, the day's earlier trading: no catalog has any, so, as for the longer ranges
(1W…ALL), a deterministic walk (seeded by the chart's name, e.g. a symbol, and the range) that
ends at the starting value. (Without it a run's first page drew a lone point: one vertical
stroke over an empty box, which no trading app shows.) Every range ends at the value shown
above it.
"""

from __future__ import annotations

import functools
import random
from collections.abc import Callable, Sequence
from dataclasses import dataclass

WIDTH, HEIGHT = 680.0, 220.0
SESSION_SAMPLES = 90
# Made-up history per range; "1D" is the day's trading before the run, as wide as its session.
HISTORY_POINTS = {"1D": 60, "1W": 40, "1M": 22, "3M": 64, "YTD": 48, "1Y": 52, "ALL": 80}
HISTORY_SWING = {
    "1D": 0.006,
    "1W": 0.03,
    "1M": 0.06,
    "3M": 0.1,
    "YTD": 0.14,
    "1Y": 0.2,
    "ALL": 0.45,
}


@dataclass(frozen=True)
class Chart:
    path: str  # SVG path data
    baseline_y: float  # where the dashed starting-value line sits
    up: bool  # the last value is at or above the first: green, else red
    first: float
    last: float


def session_samples(
    value_at: Callable[[float], float], now: float, count: int = SESSION_SAMPLES
) -> list[tuple[float, float]]:
    """`count` evenly spaced instants from the start to `now`, the last exactly `now`."""
    if now <= 0:
        return [(0.0, value_at(0.0))]
    step = now / (count - 1)
    times = [i * step for i in range(count - 1)] + [now]
    return [(t, value_at(t)) for t in times]


@functools.lru_cache(maxsize=2048)
def history(seed: str, range_name: str, ending: float) -> tuple[float, ...]:
    """A made-up past for `range_name` that ends at `ending` (walked backwards from it)."""
    rng = random.Random(f"{seed}/{range_name}")
    count, swing = HISTORY_POINTS[range_name], HISTORY_SWING[range_name]
    values, value = [ending], ending
    drift = rng.uniform(-swing, swing) / count
    for _ in range(count - 1):
        value = value * (1 - drift + rng.gauss(0, swing / count**0.5 / 2))
        values.append(max(value, ending * 0.05))
    return tuple(reversed(values))


def draw(points: Sequence[tuple[float, float]], span: float, start_value: float) -> Chart:
    """`points` (x in [0, span], value) scaled into the chart box; padding keeps the line off
    the edges and the dashed starting line inside."""
    values = [v for _, v in points] + [start_value]
    low, high = min(values), max(values)
    pad = (high - low) * 0.08 or max(abs(high) * 0.01, 0.01)
    low, high = low - pad, high + pad

    def y(v: float) -> float:
        return round(HEIGHT - (v - low) / (high - low) * HEIGHT, 2)

    def x(t: float) -> float:
        return round(t / span * WIDTH, 2) if span else 0.0

    path = " ".join(f"{'M' if i == 0 else 'L'}{x(t)},{y(v)}" for i, (t, v) in enumerate(points))
    last = points[-1][1]
    return Chart(path, y(start_value), last >= start_value, points[0][1], last)


def chart(
    seed: str, range_name: str, value_at: Callable[[float], float], now: float, span: float
) -> Chart:
    """The chart for a range: the live session for 1D, else history then today's value."""
    start = value_at(0.0)
    past = history(seed, range_name, round(start, 2))
    if range_name == "1D":
        session = max(span, now)
        step = session / (len(past) - 1)
        earlier = [(i * step, v) for i, v in enumerate(earlier_today(seed, start))]
        live = [(session + t, v) for t, v in session_samples(value_at, now)]
        return draw(earlier + live, 2 * session, start)
    values = [*past, value_at(now)]
    points = [(float(i), v) for i, v in enumerate(values)]
    return draw(points, float(len(values) - 1), values[0])


def earlier_today(seed: str, start: float) -> tuple[float, ...]:
    """The day's made-up values before the run, up to (not including) its start value."""
    return history(seed, "1D", round(start, 2))[:-1]


def sparkline(values: Sequence[float], width: float = 64.0, height: float = 24.0) -> str:
    """A small path for a list row (no axes)."""
    low, high = min(values), max(values)
    spread = (high - low) or 1.0
    step = width / max(len(values) - 1, 1)
    return " ".join(
        f"{'M' if i == 0 else 'L'}{round(i * step, 1)},{round(height - (v - low) / spread * height, 1)}"
        for i, v in enumerate(values)
    )
