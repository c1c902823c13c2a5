"""The simulated clock of a run, on the authored time scale.

Read the clock once per operation (`now = sim_now(run, wall)`) and derive every comparison
from that value. Only the functions at the edge (views, ticker) read the wall clock.
"""

from __future__ import annotations

import time

from events.models import ClockMode, Run, RunStatus


def wall_now() -> float:
    return time.time()


def sim_now(run: Run, wall: float) -> float:
    """Simulated seconds of `run` at wall time `wall`, clamped to the timeline end."""
    if run.status == RunStatus.RUNNING_AUTO and run.started_at is not None:
        return min(max(0.0, (wall - run.started_at) * run.speed_factor), run.event_timeline_end)
    # ready, running_manual (virtual clock) and completed (frozen) all read the stored value.
    return run.sim_time


def wall_due(run: Run, sim_seconds: float) -> float | None:
    """The wall time at which `sim_seconds` happens on a live clock (None if not started)."""
    if run.started_at is None or run.clock_mode != ClockMode.LIVE:
        return None
    return run.started_at + sim_seconds / run.speed_factor
