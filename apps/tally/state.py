"""The tally as an immutable value: the entries pings and pokes add, and a level that moves.

The level is a series of waypoints (apps.kit.waypoints): between scenario events it ramps with
the clock, so the page, the live push and the `levels` evaluation table all compute it from
their one `now`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from itertools import chain

from apps.kit.waypoints import Waypoints

LEVEL_START = 0.0  # the level before any waypoint
LEVEL_STEP = 0.1  # the page shows the level rounded to this

Entry = tuple[str, int, float]  # (source, n, at): what the `entries` table lists
FLAT = Waypoints(LEVEL_START)  # no waypoints yet


CHUNK = 64  # entries per kept chunk


@dataclass(frozen=True)
class TallyState:
    # The entries as full chunks and a tail: adding one copies at most a chunk's worth. A tuple
    # grown by one copies everything it holds, so folding n pokes copied n²/2 entries — and
    # bench_engine's fold figure, which folds thousands of them to time the engine, timed that.
    chunks: tuple[tuple[Entry, ...], ...] = ()
    tail: tuple[Entry, ...] = ()
    level: Waypoints = FLAT

    @property
    def entries(self) -> tuple[Entry, ...]:
        return tuple(chain(chain.from_iterable(self.chunks), self.tail))

    @property
    def total(self) -> int:
        return sum(n for _, n, _ in self.entries)

    def level_at(self, now: float) -> float:
        return self.level.value_at(now)

    def shown_level(self, now: float) -> float:
        """The level as the page shows it: rounded to LEVEL_STEP (the rounding `level_changes_at`
        assumes)."""
        return round(self.level_at(now) / LEVEL_STEP) * LEVEL_STEP

    def level_changes_at(self, now: float) -> float | None:
        """When the level as shown (rounded to LEVEL_STEP) may next change; None: never."""
        return self.level.next_change(now, step=LEVEL_STEP)


def with_entry(state: TallyState, source: str, n: int, at: float) -> TallyState:
    tail = (*state.tail, (source, n, at))
    if len(tail) < CHUNK:
        return replace(state, tail=tail)
    return replace(state, chunks=(*state.chunks, tail), tail=())


def with_level_points(state: TallyState, points) -> TallyState:
    """The level with `(time, value)` points added by the waypoint insertion rule."""
    return replace(state, level=state.level.with_points(points))
