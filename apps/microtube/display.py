"""How MicroTube writes counts and ages, as YouTube does, and when each text next changes.

Counts: "512 views", "2.3K views", "684K views", "1.4M views" (views: at most one decimal, none
from ten of a unit); "41.3K subscribers", "1.25M subscribers" (three significant digits). A
moving count is rounded to its display step first, so `Waypoints.next_change(step=…)` says
exactly when the text changes. Ages: "Just now", "1 minute ago", "3 days ago", "2 weeks ago".
"""

from __future__ import annotations

import math
from typing import Any

from apps.kit import simclock
from apps.kit.simclock import DAY_S
from apps.kit.streaming import COUNT_REFRESH_S, showing, shown_count
from apps.kit.waypoints import Waypoints

UNITS = ((1_000_000_000, "B"), (1_000_000, "M"), (1_000, "K"))
# YouTube counts months and years too: "3 months ago", "1 year ago".
AGE_UNITS = (("year", 365 * DAY_S), ("month", 30 * DAY_S), *simclock.UNITS)


def count_step(value: float, *, digits: int | None = None) -> int:
    """The display resolution of `value`: views style (digits=None) or `digits` significant."""
    value = abs(value)
    if value < 1000:
        return 1
    magnitude = 10 ** math.floor(math.log10(value))
    if digits is not None:
        return max(1, magnitude // 10 ** (digits - 1))
    unit = next(size for size, _ in UNITS if value >= size)
    return unit // 10 if value < unit * 10 else unit


def compact(value: float, *, digits: int | None = None) -> str:
    """`1_420_000` → "1.4M" (views) or "1.42M" (digits=3); below a thousand, the number."""
    step = count_step(value, digits=digits)
    shown = shown_count(value, step)
    if shown < 1000:
        return str(shown)
    size, suffix = next((s, x) for s, x in UNITS if shown >= s)
    decimals = max(0, round(math.log10(size / step)))
    text = f"{shown / size:.{decimals}f}"
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return text + suffix


def views_text(value: float) -> str:
    """From the raw (unrounded) value, so the text changes where `moving_change` says."""
    return "1 view" if shown_count(value) == 1 else f"{compact(value)} views"


def subscribers_text(value: float) -> str:
    return "1 subscriber" if shown_count(value) == 1 else f"{compact(value, digits=3)} subscribers"


def moving(page: Any, series: Waypoints, *, digits: int | None = None) -> float:
    """The value of `series` at the page's `now`; an open page shows its compact text anew at
    the refresh after it changes."""
    step = count_step(series.value_at(page.now), digits=digits)
    # YouTube refreshes view and subscriber counts on an open page every few minutes, never
    # live: a reload shows the count of the moment, a watching agent is not woken by each tick.
    return showing(page, series, step=step, refresh=COUNT_REFRESH_S)


def ago(at: float, now: float) -> str:
    return simclock.long_ago(at, now, AGE_UNITS, just_now="Just now")


def ago_changes_at(at: float, now: float) -> float:
    """When `ago(at, now)` next reads differently: the next whole unit."""
    return simclock.units_changes_at(at, now, AGE_UNITS)
