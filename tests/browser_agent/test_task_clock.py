"""A live run's task clock (apps/browser_agent/tools.TaskClock) counts on the run's own clock,
so wait_for's looks fall on the same simulated moments on every run of a task."""

from __future__ import annotations

import time

import pytest

from apps.browser_agent.sim_clock import ClockReading
from apps.browser_agent.tools import TaskClock
from apps.browser_agent.waiting import look_at


def test_it_reads_the_runs_clock_as_the_page_reported_it():
    heard = time.monotonic()
    clock = TaskClock(2.0, lambda: ClockReading(sim=41.0, rate=2.0, heard=heard))
    now = clock.now()
    assert now == pytest.approx(41.0 + (time.monotonic() - heard) * 2.0, abs=0.05)
    time.sleep(0.1)  # the only way to see a wall clock pass; nothing is waited for
    assert clock.now() - now == pytest.approx(0.2, abs=0.1)


def test_it_is_fixed_at_its_first_reading_and_never_jumps():
    readings: list[ClockReading] = []
    clock = TaskClock(1.0, lambda: readings[-1] if readings else None)
    before = clock.now()  # no page of a run yet: the wall clock
    readings.append(ClockReading(sim=3.0, rate=1.0, heard=time.monotonic()))
    assert before <= clock.now() < before + 1.0  # a reading heard later changes nothing


def test_a_sleep_to_a_look_moment_wakes_on_it():
    heard = time.monotonic()
    clock = TaskClock(20.0, lambda: ClockReading(sim=100.0, rate=20.0, heard=heard))
    moment = look_at(clock.now() + 1.0)
    clock.sleep(moment - clock.now())
    assert moment <= clock.now() < moment + 20.0  # a wall second late at most, at speed 20
