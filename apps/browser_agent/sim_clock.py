"""The run's simulated time as the server last reported it, carried forward to now.

Every page of a run answers with `X-Sentinel-Sim-Time` (the simulated second it was rendered at)
and `X-Sentinel-Sim-Rate` (simulated seconds per wall second from then on; 0 while the clock
stands) — apps.kit.sim_clock_header. A fast-forward run's wait URL answers the same two facts
(`sim_time`, `speed_factor`). The agent keeps the latest reading of either and, for each step
of its transcript, carries it forward by its rate: the step lands on the run's own clock, the
clock of the run's log and of the scenario's events, whatever the speed factor and however far
the waits skipped. Without any reading (a page of no run) a step has no simulated time.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass

SIM_TIME_HEADER = "x-sentinel-sim-time"  # as Playwright gives header names: lower case
SIM_RATE_HEADER = "x-sentinel-sim-rate"


@dataclass(frozen=True)
class ClockReading:
    sim: float  # the run's simulated seconds the server reported
    rate: float  # simulated seconds per wall second from then on
    heard: float  # time.monotonic() when the answer arrived

    def at(self, monotonic: float) -> float:
        return self.sim + max(0.0, monotonic - self.heard) * self.rate


def reading_from_headers(headers: Mapping[str, str], heard: float) -> ClockReading | None:
    """The reading a response's headers carry (names in lower case), if they carry one."""
    try:
        sim = float(headers[SIM_TIME_HEADER])
        rate = float(headers.get(SIM_RATE_HEADER, "0"))
    except (KeyError, ValueError):
        return None
    return ClockReading(sim, rate, heard)


def sim_time_now(
    *sources: Callable[[], ClockReading | None],
    monotonic: Callable[[], float] = time.monotonic,
) -> float | None:
    """The run's simulated time now, from the latest reading any source heard (None: none)."""
    readings = [reading for source in sources if (reading := source()) is not None]
    if not readings:
        return None
    return round(max(readings, key=lambda r: r.heard).at(monotonic()), 3)
