"""Every scenario of every registered environment is solvable through the site, and not passed
for free (cases.py says which scenarios: ours with their solutions, and the original's).

For a task: evaluating right after create fails; eval_sql is false just before condition_at
and true from it; carrying out the solution through the pages and contacting passes; an active
task whose eval needs an action fails without it. For a no-op: never contacting passes,
contacting fails. Graded by `events.evaluation.evaluate`; eval_sql alone is run on the grading
database `grading_snapshot(run).write` builds, as evaluation does.
"""

from __future__ import annotations

import pytest

from events import lifecycle
from events.commands import perform_action
from events.evaluation import evaluate, grading_snapshot
from events.models import Run
from events.registry import ActionRejected
from events.sandbox import is_truthy, run_eval_sql
from tests.environments.cases import params
from tests.environments.oracle import browser, contact, perform_through_pages

pytestmark = pytest.mark.django_db

JUST_BEFORE = 0.01  # simulated seconds before condition_at


def eval_sql_holds(run: Run) -> bool:
    """The scenario's eval_sql on the run as it is now, without the contact gate."""
    run.refresh_from_db()
    outcome = run_eval_sql(run.spec["eval_sql"], grading_snapshot(run).write)
    assert outcome.ok, outcome.error
    return is_truthy(outcome.value)


def perform_possible(run: Run, steps: list[dict]) -> list[dict]:
    """Perform, in order, the steps the current state allows; return the others."""
    left = []
    for step in steps:
        try:
            perform_action(run, step["action"], step["payload"])
        except ActionRejected:
            left.append(step)
    return left


@pytest.mark.parametrize("case", params(noop=False))
def test_evaluating_right_after_create_fails(case, start):
    _, run = start(case)
    verdict = evaluate(run)
    assert verdict.success is False, verdict.detail


@pytest.mark.parametrize("case", params(noop=False))
def test_eval_sql_is_false_just_before_condition_at_and_true_from_it(case, start):
    if why := case.defect("condition_at"):
        pytest.skip(f"original file whose condition_at cannot be checked: {why}")
    scenario, run = start(case)
    lifecycle.advance(run, max(0.0, scenario.condition_at - JUST_BEFORE))
    pending = perform_possible(run, list(scenario.solution))
    assert eval_sql_holds(run) is False
    if len(pending) < len(scenario.solution):
        # Some steps were possible early (an order at a moving price is, at the wrong price):
        # what must hold from condition_at is the solution performed then, on a run that did
        # not act early.
        _, run = start(case)
        pending = list(scenario.solution)
    lifecycle.advance(run, scenario.condition_at)
    pending = perform_possible(run, pending)
    assert pending == [], f"solution steps not possible at condition_at: {pending}"
    assert eval_sql_holds(run) is True


def solve_and_contact(run, scenario) -> None:
    """What a person does: the solution through the pages, then the contact page."""
    client = browser()
    for step in scenario.solution:
        perform_through_pages(client, run, step)
    contact(client, run)


@pytest.mark.parametrize("case", params(noop=False))
def test_the_solution_carried_out_through_the_pages_and_a_contact_pass(case, start):
    if why := case.defect("unreachable"):
        pytest.skip(f"original file whose condition never holds: {why}")
    scenario, run = start(case)
    lifecycle.advance(run, scenario.condition_at)
    solve_and_contact(run, scenario)
    verdict = evaluate(run)
    assert verdict.success is True, verdict.detail


@pytest.mark.parametrize("case", params(noop=False, needs_action=True))
def test_an_active_task_fails_without_its_solution(case, start):
    scenario, run = start(case)
    lifecycle.advance(run, scenario.kill_at)
    contact(browser(), run)
    verdict = evaluate(run)
    assert verdict.success is False, verdict.detail


@pytest.mark.parametrize("case", params(noop=True))
def test_a_noop_passes_when_the_agent_never_contacts(case, start):
    scenario, run = start(case)
    lifecycle.advance(run, scenario.kill_at)
    verdict = evaluate(run)
    assert verdict.success is True, verdict.detail


@pytest.mark.parametrize("case", params(noop=True))
def test_a_noop_fails_when_the_agent_contacts(case, start):
    scenario, run = start(case)
    lifecycle.advance(run, scenario.kill_at)
    solve_and_contact(run, scenario)
    verdict = evaluate(run)
    assert verdict.success is False, verdict.detail
