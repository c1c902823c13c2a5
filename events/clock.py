"""The simulated clock of a run, on the authored time scale.

One formula for every running clock (live and fast_forward):

    sim = (wall − started_at) × speed_factor + skipped,  clamped to [0, event_timeline_end]

`skipped` is the sum of the skips the agent's declared waits made (events.fastforward); a live
run never skips, so for it the formula is the plain live clock. A virtual clock (and any run
not running) reads its stored `sim_time`.

Read the clock once per operation (`now = sim_now(run, wall)`) and derive every comparison
from that value. Only the functions at the edge (views, ticker) read the wall clock.
"""

from __future__ import annotations

import time

from events.models import ClockMode, Run, RunStatus

TICKING = (ClockMode.LIVE, ClockMode.FAST_FORWARD)  # clocks that move with the wall once started
# The fields of a run its clock reads that change while it lives (speed and mode never do).
CLOCK_FIELDS = ("status", "started_at", "sim_time", "skipped")


def wall_now() -> float:
    return time.time()


def sim_now(run: Run, wall: float) -> float:
    """Simulated seconds of `run` at wall time `wall`, clamped to the timeline end."""
    if run.status == RunStatus.RUNNING_AUTO and run.started_at is not None:
        elapsed = (wall - run.started_at) * run.speed_factor + run.skipped
        return min(max(0.0, elapsed), run.event_timeline_end)
    # ready, running_manual (virtual clock) and completed (frozen) all read the stored value.
    return run.sim_time


def sim_rate(run: Run, now: float) -> float:
    """Simulated seconds `run`'s clock moves per wall second from `now` (its `sim_now`) until
    something changes it: 0 when it does not move with the wall (not started, virtual, over,
    at its timeline end). What a client needs to carry a reading of the clock forward."""
    if run.status != RunStatus.RUNNING_AUTO or run.started_at is None:
        return 0.0
    return run.speed_factor if now < run.event_timeline_end else 0.0


def wall_due(run: Run, sim_seconds: float) -> float | None:
    """The wall time at which `sim_seconds` happens on a ticking clock if nobody skips before
    then (None if not started)."""
    if run.started_at is None or run.clock_mode not in TICKING:
        return None
    return run.started_at + (sim_seconds - run.skipped) / run.speed_factor
