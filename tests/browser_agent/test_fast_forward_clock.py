"""The agent's side of a fast-forward clock (apps/browser_agent/fast_forward.py), against a
stand-in wait URL that answers as the server's does, so each rule is seen on its own: what the
agent asks for, how it reads the clock between waits, when it waits for its page, and how its
budget counts what it skipped."""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import pytest

from apps.browser_agent.fast_forward import RunClock
from apps.browser_agent.loop import WallBudget


@dataclass
class Server:
    """Answers waits from a clock at `sim`, stopping at `kill_at`; next entry at `entry`."""

    sim: float = 5.0
    kill_at: float = 630.0
    entry: float = 50.0
    speed: float = 2.0
    asked: list[dict] = field(default_factory=list)

    def post(self, body: dict) -> dict:
        self.asked.append(body)
        start = self.sim
        if "seconds" in body:
            to, why = start + body["seconds"], "slept"
        elif "until" not in body:
            to, why = max(start, body["to"]), "slept"
        else:
            horizon = max(start, body["to"]) if "to" in body else start + body["timeout"]
            entry = self.entry if self.entry > body.get("since", start) else None
            if entry is not None and entry <= horizon:
                to, why = max(start, entry), "change"
            else:
                to, why = horizon, "timeout"
        if to >= self.kill_at:
            to, why = max(start, self.kill_at), "kill_at"
        self.sim = to
        return {"from": start, "sim_time": to, "why": why, "seq": 7, "speed_factor": self.speed}


@dataclass
class Page:
    due: float | None = None
    caught_up: list[tuple[int, float]] = field(default_factory=list)

    def next_change(self) -> float | None:
        return self.due

    def catch_up(self, seq: int, now: float) -> None:
        self.caught_up.append((seq, now))


class Monotonic:
    def __init__(self) -> None:
        self.t = 100.0

    def __call__(self) -> float:
        return self.t


@pytest.fixture
def cast():
    server, page, wall = Server(), Page(), Monotonic()
    return server, page, wall, RunClock(server.post, page, monotonic=wall)


def test_the_first_reading_is_a_zero_skip_then_the_clock_runs_at_the_runs_speed(cast):
    server, page, wall, clock = cast
    assert clock.now() == 5.0 and server.asked == [{"seconds": 0}]
    wall.t += 3.0
    assert clock.now() == 5.0 + 3.0 * 2.0  # the answer's speed factor
    assert page.caught_up == []  # nothing moved: no page to wait for


def test_a_sleep_is_one_skip_and_the_page_catches_up_with_it(cast):
    server, page, _, clock = cast
    clock.sleep(40.0)
    assert server.asked == [{"seconds": 40.0}] and clock.now() == 45.0
    assert page.caught_up == [(7, 45.0)]


def test_waking_at_a_change_stops_at_the_pages_own_next_change_if_sooner(cast):
    server, page, _, clock = cast
    page.due = 20.0  # e.g. the minute turns at 20 s, before the next entry at 50 s
    assert clock.skip_to(200.0, wake_at_change=True) == 20.0 == clock.now()
    assert server.asked[-1] == {"until": "change", "to": 20.0, "since": 5.0}
    page.due = None
    assert clock.skip_to(200.0, wake_at_change=True) == 50.0 == clock.now()
    # A change since its last landing: the one that came while the agent looked at 20.
    assert server.asked[-1] == {"until": "change", "to": 200.0, "since": 20.0}


def test_a_skip_aims_at_its_moment_not_at_seconds_from_a_lagging_reading(cast):
    server, *_, clock = cast
    clock.now()
    server.sim += 0.3  # the server's clock ran on while the answer travelled
    assert clock.skip_to(40.25, wake_at_change=False) == 40.25
    assert server.asked[-1] == {"to": 40.25}


def test_a_skip_to_kill_at_says_no_further_skip_is_possible(cast):
    *_, clock = cast
    assert clock.skip_to(600.0, wake_at_change=False) == 600.0
    assert clock.skip_to(900.0, wake_at_change=False) is None
    assert clock.now() == 630.0 and clock.skipped == 625.0


def test_skipped_time_spends_the_budget_as_waiting_would_have(cast):
    *_, clock = cast
    budget = WallBudget(300.0, time.monotonic(), skipped=clock.skipped_wall)
    clock.sleep(100.0)  # 100 simulated seconds at speed 2: 50 wall seconds of waiting
    left = budget.left()
    assert left is not None and 249.0 < left <= 250.0
