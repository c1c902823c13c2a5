"""Baselines, the core's rule (upstream's): measured right after a preload applies, at the
preload's own time; the last preload wins; without a preload there are none; nothing later
moves them; eval_sql reads them as session_meta rows `baseline_<name>`.

Told with `tally`, whose baselines are its total, its number of pings and its level (which
moves with the clock, so it shows *when* a baseline is measured).
"""

from __future__ import annotations

import pytest
from django.test import Client

from apps.kit.links import contact_path
from apps.scenarios.format import parse_scenario
from apps.tally.environment import tally_scenario
from events import lifecycle
from events.commands import perform_action
from events.evaluation import evaluate, grading_snapshot
from events.models import ClockMode
from events.projection import fold_from_scratch, folded_state

pytestmark = pytest.mark.django_db

RAMP = [[0, 3.0], [100, 13.0]]  # the level: 3 at 0 s, up to 13 at 100 s


def preload(at: float, n: int, **payload) -> dict:
    return {"time": at, "type": "preload", "payload": {"n": n, **payload}}


def ping(at: float, n: int) -> dict:
    return {"time": at, "type": "ping", "payload": {"n": n}}


def run_of(*events: dict, eval_sql: str = "SELECT 1", condition_at: float | None = 90.0):
    data = tally_scenario(condition_at=condition_at, eval_sql=eval_sql)
    data["events"] = list(events)
    spec = parse_scenario(data, source="tests").to_run_spec()
    return lifecycle.create_run(spec, clock_mode=ClockMode.VIRTUAL)


def baselines(run) -> dict:
    return dict(folded_state(run).baselines)


def test_they_are_measured_right_after_the_preload():
    run = run_of(preload(0.0, 2, level_waypoints=RAMP), ping(10.0, 1))
    assert baselines(run) == {"total": 2, "pings": 1, "level": 3.0}


def test_the_last_preload_wins_measured_at_its_own_time():
    run = run_of(preload(0.0, 1, level_waypoints=RAMP), ping(10.0, 1), preload(50.0, 4))
    lifecycle.advance(run, 50.0)
    assert baselines(run) == {"total": 6, "pings": 3, "level": 8.0}


def test_without_a_preload_there_are_none():
    run = run_of(ping(0.0, 1), ping(10.0, 2), condition_at=None)
    lifecycle.advance(run, 60.0)
    assert baselines(run) == {}
    assert not any(key.startswith("baseline_") for key in grading_snapshot(run).session_meta())


def test_later_events_do_not_move_them():
    run = run_of(preload(0.0, 2, level_waypoints=RAMP), ping(10.0, 1), ping(40.0, 5))
    measured = baselines(run)
    lifecycle.advance(run, 40.0)
    perform_action(run, "poke", {"n": 3})
    lifecycle.advance(run, 80.0)  # the level has moved on to 11
    assert baselines(run) == measured
    assert dict(fold_from_scratch(run).baselines) == measured


def test_they_reach_session_meta_through_evaluation():
    def baseline(name: str, kind: str) -> str:
        key = f"baseline_{name}"
        return f"(SELECT CAST(value AS {kind}) FROM session_meta WHERE key = '{key}')"

    sql = (
        f"SELECT {baseline('total', 'INTEGER')} = 2 AND {baseline('pings', 'INTEGER')} = 1 "
        f"AND {baseline('level', 'REAL')} = 3.0"
    )
    run = run_of(preload(0.0, 2, level_waypoints=RAMP), ping(10.0, 1), eval_sql=sql)
    lifecycle.advance(run, 90.0)
    assert Client().get(contact_path(run)).status_code == 200
    verdict = evaluate(run)
    assert verdict.success is True, verdict.detail
