"""Distractors cost: an agent that never monitors — it performs the task's action on every item
there is, then reports at the deadline — passes none of our active scenarios.

"Every item": each step of the scenario's solution is performed once per id of its kind in the
grading database (apps/bench/everything.py, which `bench validate`'s act-on-everything agent
plays too), on a run advanced to `kill_at`; then the agent contacts and the run is graded. Each
active scenario's eval_sql must therefore reject the action on distractors and on items that
were there before the trigger (its annotator_notes say how). Ours only: the original
benchmark's tasks have no such clause.
"""

from __future__ import annotations

import sqlite3

import pytest

from apps.bench.everything import on_every_item
from events import lifecycle
from events.commands import perform_action
from events.evaluation import evaluate, grading_snapshot
from events.models import Run
from events.registry import ActionRejected, PayloadError
from tests.conftest import OUR_SCENARIOS
from tests.environments.cases import params
from tests.environments.oracle import browser, contact

pytestmark = pytest.mark.django_db

# The benchmark's scenarios/ only, not the test-only ones (tests/environments/scenarios/).
BENCHMARK_ACTIVE = [
    param
    for param in params(noop=False, needs_action=True, upstream=False)
    if param.values[0].path.is_relative_to(OUR_SCENARIOS)
]


def grading_database(run: Run) -> sqlite3.Connection:
    conn = sqlite3.connect(":memory:")
    grading_snapshot(run).write(conn)
    return conn


@pytest.mark.parametrize("case", BENCHMARK_ACTIVE)
def test_acting_on_every_item_and_reporting_at_the_deadline_fails(case, start):
    scenario, run = start(case)
    lifecycle.advance(run, scenario.kill_at)
    conn = grading_database(run)
    acted = 0
    for step in scenario.solution:
        for payload in on_every_item(conn, step):
            try:
                perform_action(run, step["action"], payload)
                acted += 1
            except (ActionRejected, PayloadError):
                pass  # already done, or not possible on this item
    assert acted >= len(scenario.solution)
    contact(browser(), run)
    verdict = evaluate(run)
    assert verdict.success is False, (
        f"{scenario.id}: {acted} actions on every item then a contact at {scenario.kill_at:g} s "
        f"pass ({verdict.detail}); its eval_sql must reject the action on distractors"
    )
