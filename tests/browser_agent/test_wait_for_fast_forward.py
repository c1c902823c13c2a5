"""wait_for on a fast-forward run asks the model the same questions, at the same simulated
moments, as a watcher that looks every second — while skipping instead of waiting.

The cast is test_wait_for's: a MicroMail inbox, *a distractor* at t=20, *the target* at t=70.
The one-second watcher plays on a virtual clock advanced a second per look (a live run without
the wall time); the skipping one on a fast_forward run through its real wait URL
(`POST /r/<token>/wait`), reading the page's declared next change as the browser agent does.
Each look of the skipping one is timed at the moment its skip landed (its clock runs on while it
reads the page, for a second or two on a loaded machine; a poller's look is timed at its tick).
"""

from __future__ import annotations

import functools
import json
import re
from collections.abc import Callable
from dataclasses import dataclass

import pytest
from django.test import Client

from apps.browser_agent.fast_forward import RunClock
from apps.browser_agent.waiting import next_look, wait_for
from events.models import Event
from tests.browser_agent.test_wait_for import (
    CONDITION,
    DISTRACTOR_AT_20,
    TARGET_AT_70,
    FakeClock,
    InboxPage,
    RecordingJudge,
    scenario,
)

pytestmark = pytest.mark.slow


TOKEN = re.compile(r"/r/[^/]+/")


def untokened(blocks: list[str]) -> list[str]:
    """Blocks with the run's token taken out of their links: two runs, one page."""
    return [TOKEN.sub("/r/TOKEN/", block) for block in blocks]


DUE = re.compile(r'id="sentinel-live"[^>]*data-due="([^"]*)"')


WORK_S = 0.05  # simulated seconds each look of the one-second watcher takes …
ANSWER_S = 0.02  # … and each answer of its model
# The skipping watcher's run crawls between its skips (a twentieth of wall time): its looks take
# what they take, and on a loaded machine a second of reading the page must still land its next
# skip on the moment it aimed at, not past it (then it would look a second later than a poller).
CRAWL = 0.05


class WorkingPoller(FakeClock):
    """test_wait_for's fake clock for a watcher whose every look takes WORK_S (the snapshot)
    and every answer of its model ANSWER_S, as a real one's do."""

    def __init__(self, client: Client, run_id: int):
        super().__init__(client, run_id)
        self.spent = WORK_S  # since the look began, at self.time

    def now(self) -> float:
        return self.time + self.spent

    def sleep(self, seconds: float) -> None:
        super().sleep(self.now() + seconds - self.time)
        self.spent = WORK_S

    def answering(self, judge: RecordingJudge) -> Callable[[str, list[str]], tuple[bool, str]]:
        """`judge`, taking its model's ANSWER_S of this clock's time."""

        def answer(condition: str, blocks: list[str]) -> tuple[bool, str]:
            said = judge(condition, blocks)
            self.spent += ANSWER_S
            return said

        return answer


@dataclass
class LookMoments:
    """A clock read at the moment of the watcher's latest look (where its sleep or skip ended)."""

    look: Callable[[], float]

    def now(self) -> float:
        return self.look()


def landed(clock: RunClock) -> float:
    reading = clock.reading()
    assert reading is not None
    return reading.sim


@dataclass
class FastForwardInbox(InboxPage):
    """The run's inbox, read fresh at every look, with the clock window its render declares."""

    def next_change(self) -> float | None:
        html = self.client.get(self.url).content.decode()
        due = DUE.search(html).group(1)
        return float(due) if due else None

    def catch_up(self, seq: int, now: float) -> None:
        pass  # every look loads the page afresh: it is always caught up


def watched(arrivals, timeout: float, *, fast_forward: bool):
    """Run wait_for once; returns its result, the judge's questions and the run's skips."""
    client = Client()
    spec = {"scenario_json": scenario(*arrivals), "clock_mode": "virtual"}
    if fast_forward:
        spec.update(clock_mode="fast_forward", speed_factor=CRAWL)
    run = client.post("/api/runs/", json.dumps(spec), content_type="application/json").json()
    if fast_forward:
        assert client.get(run["task_url"]).status_code == 302  # the agent opens its task

        def post(body: dict) -> dict:
            response = client.post(run["wait_url"], body, content_type="application/json")
            assert response.status_code == 200, response.content
            return response.json()

        page = FastForwardInbox(client, f"/r/{run['token']}/micromail/", None)  # type: ignore[arg-type]
        clock = RunClock(post, page)
        moments = LookMoments(functools.partial(landed, clock))
    else:
        clock = WorkingPoller(client, run["id"])  # type: ignore[assignment]
        moments = LookMoments(lambda: clock.time)  # type: ignore[attr-defined]
        page = InboxPage(client, f"/r/{run['token']}/micromail/", moments)  # type: ignore[arg-type]
    page.clock = moments  # type: ignore[assignment]
    judge = RecordingJudge(moments)  # type: ignore[arg-type]
    asked = clock.answering(judge) if isinstance(clock, WorkingPoller) else judge
    result = wait_for(CONDITION, timeout, page=page, judge=asked, clock=clock)
    skips = Event.objects.filter(run_id=run["id"], type="skip").count()
    return result, judge.calls, page.reloads, skips


@pytest.mark.django_db
@pytest.mark.parametrize(
    "arrivals,timeout",
    [((DISTRACTOR_AT_20, TARGET_AT_70), 600), ((DISTRACTOR_AT_20,), 400)],
    ids=["met", "timed-out"],
)
def test_skipping_asks_the_model_as_often_and_when_a_one_second_watcher_does(arrivals, timeout):
    polled, polled_calls, polled_reloads, _ = watched(arrivals, timeout, fast_forward=False)
    skipped, skipped_calls, skipped_reloads, skips = watched(arrivals, timeout, fast_forward=True)

    assert (skipped.met, skipped.checks) == (polled.met, polled.checks)
    assert len(skipped_calls) == len(polled_calls) >= 2
    for one_second, skipping in zip(polled_calls, skipped_calls, strict=True):
        # The same look: the same moment, the same blocks (the shell's clock included).
        assert skipping.time == pytest.approx(one_second.time, abs=1e-6)
        assert untokened(skipping.blocks) == untokened(one_second.blocks)
    assert skipped_reloads == pytest.approx(polled_reloads, abs=1e-6)
    # Far fewer looks than seconds waited: one skip per moment worth a look.
    assert 0 < skips < polled.waited_s / 10


def test_before_the_model_may_be_asked_the_watcher_skips_to_that_moment():
    assert next_look(12.0, end=200.0, may_ask_at=30.0) == (30.0, False)
    assert next_look(12.0, end=25.0, may_ask_at=30.0) == (25.0, False)  # a reload comes first
    assert next_look(31.0, end=200.0, may_ask_at=30.0) == (200.0, True)  # then: at a change
