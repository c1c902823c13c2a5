"""wait_for's loop on a real MicroMail inbox whose run plays a small scenario.

The cast: *a distractor* (Ingrid Solberg's travel policy) arrives at t=20, *the target*
(Kevin Lee's expense reminder) at t=70. Time is fake: every sleep of wait_for advances the
run's virtual clock by the same amount through the control API, so the scenario's events fire
as the wait goes on, and the page is the server's real inbox converted to markdown.

The shell's clock and the "N min ago" labels also change once a simulated minute, giving
blocks of their own (waiting.py says why they are kept): the assertions hold whatever the
number of such blocks, and the judge answers on the target's name only.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from itertools import pairwise

import pytest
from django.test import Client

from apps.browser_agent.snapshot import html_to_markdown
from apps.browser_agent.waiting import (
    NO_CHANGES,
    PAPER_SCHEDULE,
    look_at,
    next_look_after,
    unified_diff_blocks,
    wait_for,
)

pytestmark = pytest.mark.slow


DISTRACTOR = "Ingrid Solberg"
TARGET = "Kevin Lee"
CONDITION = f"an email from {TARGET} arrives"
WHY = f"{TARGET} wrote about expense reports"


def scenario(*arrivals: tuple[float, str]) -> dict:
    return {
        "id": "wait-for-inbox",
        "environment": "micromail",
        "prompt": f"Tell me when I get an email from {TARGET}.",
        "start_page": "HOST_ADDRESS/micromail",
        "condition_at": None,
        "event_timeline_end": 3000.0,
        "kill_at": 3000.0,
        "taxonomy": {},
        "events": [
            {
                "time": 0.0,
                "type": "preload_emails",
                "payload": {"email_ids": ["base-01", "base-05", "cc-01"]},
            },
            *(
                {"time": at, "type": "new_email", "payload": {"email_id": email_id}}
                for at, email_id in arrivals
            ),
        ],
    }


DISTRACTOR_AT_20 = (20.0, "base-36")
TARGET_AT_70 = (70.0, "base-77")


class FakeClock:
    """Fake seconds that are also the run's simulated seconds: sleeping advances both."""

    def __init__(self, client: Client, run_id: int):
        self.client = client
        self.run_id = run_id
        self.time = 0.0

    def now(self) -> float:
        return self.time

    def sleep(self, seconds: float) -> None:
        self.time += seconds
        response = self.client.post(
            f"/api/runs/{self.run_id}/advance/",
            json.dumps({"time": self.time}),
            content_type="application/json",
        )
        assert response.status_code == 200, response.content


@dataclass
class InboxPage:
    """The run's inbox. A live page shows the server's current state at every snapshot (the
    real pages update themselves); a static one only what its last load showed."""

    client: Client
    url: str
    clock: FakeClock
    live: bool = True
    loaded: str = ""
    snapshots: list[str] = field(default_factory=list)
    reloads: list[float] = field(default_factory=list)

    def __post_init__(self):
        self.load()

    def load(self) -> None:
        response = self.client.get(self.url)
        assert response.status_code == 200
        self.loaded = html_to_markdown(response.content.decode())

    def markdown(self) -> str:
        if self.live:
            self.load()
        self.snapshots.append(self.loaded)
        return self.loaded

    def reload(self) -> None:
        self.reloads.append(self.clock.now())
        self.load()


@dataclass
class Call:
    time: float
    blocks: list[str]


@dataclass
class RecordingJudge:
    """Says yes when a block adds a line naming the target, and remembers every question."""

    clock: FakeClock
    calls: list[Call] = field(default_factory=list)

    def __call__(self, condition: str, blocks: list[str]) -> tuple[bool, str]:
        assert condition == CONDITION
        self.calls.append(Call(self.clock.now(), list(blocks)))
        if any(added(block, TARGET) for block in blocks):
            return True, WHY
        return False, f"no email from {TARGET} yet"


def added(block: str, text: str) -> bool:
    return any(line.startswith("+") and text in line for line in block.splitlines())


@pytest.fixture
def inbox(db):
    """`inbox(*arrivals, live=True)` → (page, clock, judge) over a new virtual-clock run."""

    def make(*arrivals: tuple[float, str], live: bool = True):
        client = Client()
        run = client.post(
            "/api/runs/",
            json.dumps({"scenario_json": scenario(*arrivals), "clock_mode": "virtual"}),
            content_type="application/json",
        ).json()
        clock = FakeClock(client, run["id"])
        page = InboxPage(client, f"/r/{run['token']}/micromail/", clock, live=live)
        return page, clock, RecordingJudge(clock)

    return make


def check_interval_after(answers: int) -> float:
    """The rate limit once the model has said "no" `answers` times: 10, 20, 40, 60, 60, …"""
    return min(PAPER_SCHEDULE.first_check * 2**answers, PAPER_SCHEDULE.max_check)


def test_the_model_sees_only_new_blocks_no_faster_than_the_rate_limit(inbox):
    page, clock, judge = inbox(DISTRACTOR_AT_20, TARGET_AT_70)

    wait_for(CONDITION, 600, page=page, judge=judge, clock=clock)

    # Nothing changes before the distractor: the first question is about it, at the first look
    # after it arrives.
    first = judge.calls[0]
    assert first.time == look_at(20) == 20.25
    assert any(added(block, DISTRACTOR) for block in first.blocks)
    shown: set[str] = set()
    for call in judge.calls:
        assert call.blocks, "asked with nothing new"
        assert shown.isdisjoint(call.blocks), f"at {call.time}: a block shown before"
        shown.update(call.blocks)
    for answers, (earlier, later) in enumerate(pairwise(judge.calls), start=1):
        assert later.time - earlier.time >= check_interval_after(answers)
    # The target's blocks wait for the rate limit, then go out at the first moment it allows:
    # the first look after the last answer (at once, on this fake clock) and its interval.
    *_, before, last = judge.calls
    assert last.time == max(
        look_at(TARGET_AT_70[0]),
        next_look_after(before.time + check_interval_after(len(judge.calls) - 1)),
    )
    assert any(added(block, TARGET) for block in last.blocks)


def test_a_met_condition_returns_at_once_with_the_models_explanation(inbox):
    page, clock, judge = inbox(DISTRACTOR_AT_20, TARGET_AT_70)

    result = wait_for(CONDITION, 600, page=page, judge=judge, clock=clock)

    assert (result.met, result.explanation) == (True, WHY)
    assert result.checks == len(judge.calls)
    assert result.waited_s == judge.calls[-1].time == clock.now()  # not one more sleep
    assert result.reloads == 0 and page.reloads == []


def test_reloads_come_at_180_then_every_doubled_interval_up_to_480(inbox):
    page, clock, judge = inbox(live=False)

    result = wait_for(CONDITION, 1100, page=page, judge=judge, clock=clock)

    # 180, +360, +480 (the cap), then the final reload when the timeout runs out: each at the
    # first look from then on.
    assert page.reloads == [180.25, 540.25, 1020.25, 1100.25]
    assert result.reloads == 4
    assert not result.met


def test_a_static_page_shows_the_target_after_its_reload(inbox):
    page, clock, judge = inbox(TARGET_AT_70, live=False)

    result = wait_for(CONDITION, 600, page=page, judge=judge, clock=clock)

    assert result.met
    assert page.reloads == [180.25]
    assert [call.time for call in judge.calls] == [180.25]


def test_the_final_check_after_the_timeout_gets_every_block(inbox):
    page, clock, judge = inbox(DISTRACTOR_AT_20)

    result = wait_for(CONDITION, 50, page=page, judge=judge, clock=clock)

    during, final = judge.calls
    assert during.time == 20.25
    assert page.reloads == [50.25] and final.time == 50.25
    assert final.blocks == unified_diff_blocks(page.snapshots[0], page.snapshots[-1])
    assert set(during.blocks) <= set(final.blocks)  # already shown, and shown again
    assert (result.met, result.checks, result.waited_s) == (False, 2, 50.25)
    assert result.explanation == f"no email from {TARGET} yet"


def test_no_change_before_the_timeout_means_no_question(inbox):
    page, clock, judge = inbox()

    result = wait_for(CONDITION, 30, page=page, judge=judge, clock=clock)

    assert judge.calls == []
    assert (result.met, result.explanation, result.checks) == (False, NO_CHANGES, 0)
    assert page.reloads == [30.25]


def test_a_negative_timeout_is_refused(inbox):
    page, clock, judge = inbox()
    with pytest.raises(ValueError, match="timeout must be a finite number"):
        wait_for(CONDITION, -1, page=page, judge=judge, clock=clock)


def test_looks_fall_a_quarter_past_each_second_of_the_runs_clock():
    assert [look_at(t) for t in (0.0, 0.25, 0.2500000001, 0.3, 20.0, 69.9)] == [
        0.25, 0.25, 0.25, 1.25, 20.25, 70.25,
    ]  # fmt: skip
    # After a look, the next: never the same moment twice, never a second skipped.
    assert [next_look_after(t) for t in (0.0, 0.25, 0.7, 1.24)] == [0.25, 1.25, 1.25, 1.25]
    # Never on a whole or tenth second, where scenario entries and the minute fall.
    assert all(round(look_at(t / 10) * 10) != look_at(t / 10) * 10 for t in range(1000))
