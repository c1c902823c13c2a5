"""Grading: the sandbox, contact timing, no-op semantics, grading as of first contact."""

from __future__ import annotations

import time

import pytest
from django.test import Client

from events import lifecycle
from events.commands import perform_action
from events.evaluation import evaluate
from events.models import ClockMode

pytestmark = pytest.mark.django_db


def manual_run(tally_spec, **kwargs):
    return lifecycle.create_run(tally_spec(**kwargs), clock_mode=ClockMode.VIRTUAL)


HOSTILE_SQL = {
    "delete": ("DELETE FROM entries", "not authorized"),
    "attach": ("ATTACH DATABASE '/tmp/sentinel-attack.db' AS evil", "not authorized"),
    "writable_schema": ("PRAGMA writable_schema=1", "not authorized"),
    "two statements": ("SELECT 1; SELECT 2", "one statement"),
    "runaway recursive CTE": (
        "WITH RECURSIVE c(x) AS (SELECT 1 UNION ALL SELECT x + 1 FROM c) SELECT max(x) FROM c",
        "time limit",
    ),
    "syntax": ("SELEC nonsense", "syntax error"),
}


@pytest.mark.parametrize("name", HOSTILE_SQL)
def test_hostile_eval_sql_fails_cleanly_and_quickly(tally_spec, name):
    sql, needle = HOSTILE_SQL[name]
    run = manual_run(tally_spec, eval_sql=sql)
    lifecycle.advance(run, 40)
    lifecycle.contact(run, method="GET")
    started = time.monotonic()
    verdict = evaluate(run)
    assert time.monotonic() - started < 3.0
    assert verdict.success is False
    assert needle in verdict.detail.lower() or needle in verdict.detail
    # The server is still healthy: the next evaluation of a sane query works.
    assert Client().get("/status").status_code == 200


def test_contact_just_after_the_condition_passes_and_just_before_fails(tally_spec):
    after = manual_run(tally_spec)
    lifecycle.advance(after, 30.1)
    lifecycle.contact(after, method="GET")
    assert evaluate(after).success is True

    before = manual_run(tally_spec, condition_at=30.0, pings=[(0.0, 1), (10.0, 1), (29.9, 1)])
    lifecycle.advance(before, 29.9)
    lifecycle.contact(before, method="GET")
    verdict = evaluate(before)
    assert verdict.success is False
    assert "before the condition held" in verdict.detail


def test_contact_times_are_floats_not_truncated(tally_spec):
    run = manual_run(tally_spec, condition_at=30.0)
    lifecycle.advance(run, 30.4)
    lifecycle.contact(run, method="GET")
    verdict = evaluate(run)
    assert verdict.contact_get_time == pytest.approx(30.4)
    assert verdict.reaction_time == pytest.approx(0.4)


def test_an_action_after_contact_does_not_change_the_verdict(tally_spec):
    sql = "SELECT EXISTS(SELECT 1 FROM entries WHERE source = 'poke')"
    run = manual_run(tally_spec, eval_sql=sql)
    lifecycle.advance(run, 31)
    lifecycle.contact(run, method="GET")
    perform_action(run, "poke", {"n": 1})  # too late: the agent already said it was done
    assert evaluate(run).success is False

    acted = manual_run(tally_spec, eval_sql=sql)
    lifecycle.advance(acted, 31)
    perform_action(acted, "poke", {"n": 1})
    lifecycle.contact(acted, method="GET")
    assert evaluate(acted).success is True


def test_noop_passes_without_contact_and_fails_with_it(tally_spec):
    quiet = manual_run(tally_spec, condition_at=None, eval_sql=None)
    lifecycle.advance(quiet, 630)
    assert evaluate(quiet).success is True

    chatty = manual_run(tally_spec, condition_at=None, eval_sql=None)
    lifecycle.advance(chatty, 630)
    lifecycle.contact(chatty, method="GET")
    verdict = evaluate(chatty)
    assert verdict.success is False
    assert "no-op" in verdict.detail


def test_noop_with_eval_sql_also_needs_the_sql_to_hold(tally_spec):
    run = manual_run(
        tally_spec, condition_at=None, eval_sql="SELECT COUNT(*) = 0 FROM entries WHERE n > 100"
    )
    lifecycle.advance(run, 630)
    assert evaluate(run).success is True


def test_never_contacting_fails_a_normal_task(tally_spec):
    run = manual_run(tally_spec)
    lifecycle.advance(run, 630)
    verdict = evaluate(run)
    assert verdict.success is False and "never visited /contact" in verdict.detail


def test_baselines_reach_session_meta(tally_spec):
    sql = "SELECT CAST(value AS INTEGER) = 1 FROM session_meta WHERE key = 'baseline_total'"
    run = manual_run(tally_spec, eval_sql=sql)
    lifecycle.advance(run, 60)
    lifecycle.contact(run, method="GET")
    assert evaluate(run).success is True


def test_text_zero_is_false_unlike_upstream(tally_spec):
    run = manual_run(tally_spec, eval_sql="SELECT '0'")
    lifecycle.advance(run, 40)
    lifecycle.contact(run, method="GET")
    assert evaluate(run).success is False


def test_evaluate_counts_views_and_actions(tally_spec):
    from events.commands import record_view

    run = manual_run(tally_spec)
    lifecycle.advance(run, 31)
    record_view(run, "/r/x/tally", at=0.0)
    perform_action(run, "poke", {"n": 2})
    verdict = evaluate(run)
    assert (verdict.views, verdict.actions) == (1, 1)
