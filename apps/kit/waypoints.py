"""Values that move between events: a series of `(time, value)` waypoints, linear in between.

A stock price or a star count is not an event fired every tick: it is a function of the state
(its waypoints) and `now`. Page, live push and evaluation all call `value_at(now)` with the one
`now` of their operation, so they agree to the digit.

The original's rule (SentinelBench's price and star models), kept exactly:
- no waypoints: flat at the starting value;
- at or before the first waypoint: the first value; at or after the last: the last value;
- in between: the last point with time ≤ now (right bisect) and the next one, linearly:
  v0 + (v1 − v0) × (now − t0) / (t1 − t0);
- a point added to an empty series at a time > 0 is preceded by a seed `(0, start)`, so the value
  ramps from the starting value; a new point goes after every point with the same or an earlier
  time (ties keep the order they were added in).

A series is immutable (reducers return a new one), so it can live in an environment's state.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from functools import cached_property


@dataclass(frozen=True)
class Waypoints:
    start: float  # the value before any waypoint (a catalog price, an initial star count)
    points: tuple[tuple[float, float], ...] = ()  # (time, value), sorted by time

    @cached_property
    def times(self) -> tuple[float, ...]:
        # Computed once per series (it is immutable): value_at runs on every price read.
        return tuple(t for t, _ in self.points)

    def with_point(self, at: float, value: float) -> Waypoints:
        """This series with `(at, value)` added by the original's insertion rule."""
        points = list(self.points)
        if not points and at > 0:
            points.append((0.0, self.start))
        index = bisect.bisect_right([t for t, _ in points], at)
        points.insert(index, (float(at), float(value)))
        return Waypoints(self.start, tuple(points))

    def with_points(self, pairs) -> Waypoints:
        """Several points at once (a preload's bulk waypoints), each by the insertion rule."""
        series = self
        for at, value in pairs:
            series = series.with_point(at, value)
        return series

    def value_at(self, now: float) -> float:
        points = self.points
        if not points:
            return self.start
        if now <= points[0][0]:
            return points[0][1]
        if now >= points[-1][0]:
            return points[-1][1]
        index = bisect.bisect_right(self.times, now)
        (t0, v0), (t1, v1) = points[index - 1], points[index]
        if t1 == t0:
            return v1
        return v0 + (v1 - v0) * (now - t0) / (t1 - t0)

    def next_change(self, now: float, *, step: float | None = None) -> float | None:
        """A simulated time after `now` by which what is shown of the value may have changed;
        None when it never changes again. Never later than the real change (a live page is
        re-rendered then), possibly earlier (the re-render then shows the same value).

        Shown exactly (`step=None`), a ramp changes all the time: the answer is `now` itself
        and the caller's refresh cap decides. Shown rounded to `step` (1 for a count, 0.01 for
        a price), it is when the ramp crosses the next rounding boundary.
        """
        points = self.points
        if not points or now >= points[-1][0]:
            return None
        index = bisect.bisect_right(self.times, now)
        if index == 0:
            return points[0][0]  # flat at the first value until the first point
        (t0, v0), (t1, v1) = points[index - 1], points[index]
        if v1 == v0:
            return t1
        if step is None:
            return now
        shown = round(self.value_at(now) / step)
        boundary = (shown + (0.5 if v1 > v0 else -0.5)) * step
        crossing = t0 + (boundary - v0) * (t1 - t0) / (v1 - v0)
        return min(t1, max(crossing, math.nextafter(now, math.inf)))

    def first_reach(
        self, level: float, *, after: float, until: float, rising: bool
    ) -> float | None:
        """The first time in [after, until] at which the value is at or above `level` (`rising`)
        or at or below it, exactly on the ramps; None if it does not get there. A resting limit
        order fills then. The series is right-continuous: a jump counts at its own time."""
        reached = (lambda v: v >= level) if rising else (lambda v: v <= level)
        before, value = after, self.value_at(after)
        if reached(value):
            return after
        times = self.times
        for at in sorted({t for t in times if after < t < until} | {until}):
            if at <= after:
                continue
            index = bisect.bisect_left(times, at)
            # The ramp arrives at the first point at `at` (its left limit); later ties jump.
            arriving = times[index] == at if index < len(times) else False
            left = self.points[index][1] if arriving else self.value_at(at)
            if reached(left) and left != value:
                crossing = before + (level - value) * (at - before) / (left - value)
                return min(max(crossing, before), at)
            value, before = self.value_at(at), at
            if reached(value):
                return at
        return None


def growing(start: float, growth: Iterable[Sequence[float]] | None, since: float) -> Waypoints:
    """A catalogued count that climbs while a run lasts: `start` until `since` (when its item
    arrived), then along `growth`, the catalog's `[[seconds after since, value], …]`; without
    growth points, flat at `start` (the original's behaviour)."""
    if not growth:
        return Waypoints(start)
    points = [(since, start), *((since + float(dt), float(value)) for dt, value in growth)]
    return Waypoints(start).with_points(points)
