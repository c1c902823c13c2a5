"""The test environment's own behaviour: a level that moves between waypoints, shown rounded on
the page (which says when that changes), materialised at `now`; the Poke form's refusals."""

from __future__ import annotations

import re
import sqlite3

import pytest
from django.test import Client
from django.utils.html import escape

from apps.kit.links import environment_root
from apps.scenarios.format import parse_scenario
from apps.tally.environment import tally_scenario
from events import lifecycle
from events.evaluation import grading_snapshot
from events.models import ClockMode
from events.projection import state_at

pytestmark = pytest.mark.django_db


@pytest.fixture
def level_run():
    """The level ramps from 2 (0 s) to 12 (200 s), then a `level 1` event lands at 400 s."""
    data = tally_scenario(condition_at=None, eval_sql=None)
    data["events"] = [
        {
            "time": 0.0,
            "type": "preload",
            "payload": {"n": 1, "level_waypoints": [[0, 2], [200, 12]]},
        },
        {"time": 400.0, "type": "level", "payload": {"value": 1.0}},
    ]
    spec = parse_scenario(data, source="tests").to_run_spec()
    return lifecycle.create_run(spec, clock_mode=ClockMode.VIRTUAL)


def test_the_page_shows_the_level_rounded_and_when_that_next_changes(level_run):
    lifecycle.advance(level_run, 110.0)
    html = Client().get(f"{environment_root(level_run)}/").content.decode()
    assert '<output id="level">7.5</output>' in html
    due = float(re.search(r'data-due="([^"]+)"', html).group(1))
    assert due == pytest.approx(111.0)  # the level reaches 7.55, shown 7.6


def test_a_level_event_adds_a_waypoint_at_its_own_time(level_run):
    lifecycle.advance(level_run, 300.0)
    assert state_at(level_run).level_at(300.0) == 12.0  # flat after the last waypoint
    lifecycle.advance(level_run, 400.0)
    assert state_at(level_run).level_at(400.0) == 1.0
    assert state_at(level_run).level_changes_at(400.0) is None


def test_the_levels_table_holds_the_level_at_now(level_run):
    conn = sqlite3.connect(":memory:")
    grading_snapshot(level_run, now=50.0).write(conn)
    assert conn.execute("SELECT value FROM levels").fetchall() == [(4.5,)]


@pytest.mark.parametrize(
    ("typed", "message"),
    [("abc", "n must be a whole number, got 'abc'"), ("0", "n must be a positive integer")],
)
def test_a_poke_the_tally_refuses_is_a_400_naming_n(level_run, typed, message):
    client = Client()
    client.get(f"{environment_root(level_run)}/")
    response = client.post(f"{environment_root(level_run)}/poke", {"n": typed})
    assert response.status_code == 400
    assert escape(message) in response.content.decode()  # the site's refusal page
