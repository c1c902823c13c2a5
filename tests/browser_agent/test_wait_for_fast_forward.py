"""wait_for on a fast-forward run asks the model the same questions, at the same simulated
moments, as a watcher that looks every second — while skipping instead of waiting.

The cast is test_wait_for's: a MicroMail inbox, *a distractor* at t=20, *the target* at t=70.
The one-second watcher plays on a virtual clock advanced a second per look (a live run without
the wall time); the skipping one on a fast_forward run through its real wait URL
(`POST /r/<token>/wait`), reading the page's declared next change as the browser agent does.
"""

from __future__ import annotations

import json
import re
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
    InboxPage,
    RecordingJudge,
    scenario,
)

pytestmark = pytest.mark.slow


DUE = re.compile(r'id="sentinel-live"[^>]*data-due="([^"]*)"')


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
    mode = "fast_forward" if fast_forward else "virtual"
    run = client.post(
        "/api/runs/",
        json.dumps({"scenario_json": scenario(*arrivals), "clock_mode": mode}),
        content_type="application/json",
    ).json()
    if fast_forward:
        assert client.get(run["task_url"]).status_code == 302  # the agent opens its task

        def post(body: dict) -> dict:
            response = client.post(run["wait_url"], body, content_type="application/json")
            assert response.status_code == 200, response.content
            return response.json()

        page = FastForwardInbox(client, f"/r/{run['token']}/micromail/", None)  # type: ignore[arg-type]
        clock = RunClock(post, page)
        page.clock = clock  # type: ignore[assignment]
    else:
        from tests.browser_agent.test_wait_for import FakeClock

        clock = FakeClock(client, run["id"])  # type: ignore[assignment]
        page = InboxPage(client, f"/r/{run['token']}/micromail/", clock)  # type: ignore[arg-type]
    judge = RecordingJudge(clock)  # type: ignore[arg-type]
    result = wait_for(CONDITION, timeout, page=page, judge=judge, clock=clock)
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
        # A watcher looking every second sees a change up to a second after it happens; the
        # skipping one a moment after it skipped there (its clock runs while it reads the page,
        # a second or two on a fully loaded machine). A wrong skip is off by a reload interval.
        assert one_second.time == pytest.approx(skipping.time, abs=3.0)
    assert len(skipped_reloads) == len(polled_reloads)
    assert skipped_reloads == pytest.approx(polled_reloads, abs=3.0)
    # Far fewer looks than seconds waited: one skip per moment worth a look.
    assert 0 < skips < polled.waited_s / 10


def test_before_the_model_may_be_asked_the_watcher_skips_to_that_moment():
    assert next_look(12.0, end=200.0, may_ask_at=30.0) == (30.0, False)
    assert next_look(12.0, end=25.0, may_ask_at=30.0) == (25.0, False)  # a reload comes first
    assert next_look(31.0, end=200.0, may_ask_at=30.0) == (200.0, True)  # then: at a change
