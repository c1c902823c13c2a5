"""Speed factors and kill times (upstream-protocol.md §3, §9)."""

from __future__ import annotations

import pytest
from rest_framework.test import APIClient

from events.timing import KILL_AT, SpeedFactorError, kill_at_wall, validate_speed_factor


@pytest.mark.parametrize("value", [1.0, 4.0, 0.1, 2.5])
def test_speed_factors_within_the_limits_are_accepted(value):
    assert validate_speed_factor(value) == value


@pytest.mark.parametrize(
    "value,needle",
    [
        (8.0, "above MAX_SPEED_FACTOR"),
        (0, "must be positive"),
        (-1, "must be positive"),
        (float("nan"), "must be positive"),
    ],
)
def test_speed_factors_outside_the_limits_name_the_limit(value, needle):
    with pytest.raises(SpeedFactorError, match=needle):
        validate_speed_factor(value)


@pytest.mark.parametrize(
    "sf,expected", [(4.0, 180), (2.0, 330), (1.0, 630), (0.5, 1230), (0.25, 2430)]
)
def test_kill_at_wall_table(sf, expected):
    assert kill_at_wall(sf) == pytest.approx(expected)
    assert kill_at_wall(sf) - 600 / sf == pytest.approx(30)


def test_kill_at_wall_at_speed_one_is_kill_at():
    assert kill_at_wall(1.0) == KILL_AT == 630


@pytest.mark.django_db
@pytest.mark.parametrize(
    "sf,events,condition_at,end,expected_events,expected_condition,expected_end",
    [
        (2.0, [4, 300], 600, 720, [2.0, 150.0], 300.0, 360.0),
        (0.5, [10], 300, 720, [20.0], 600.0, 1440.0),
        (None, [42], 600, 720, [42.0], 600.0, 720.0),
    ],
)
def test_init_reports_times_scaled_to_wall_seconds(
    sf, events, condition_at, end, expected_events, expected_condition, expected_end
):
    api = APIClient()
    body = {
        "environment": "tally",
        "event_timeline_end": end,
        "condition_at": condition_at,
        "events": [{"time": t, "type": "ping", "payload": {"n": 1}} for t in events],
        "eval_sql": "SELECT 1",
    }
    if sf is not None:
        body["speed_factor"] = sf
    assert api.post("/init", body, format="json").json()["next_event_time"] == expected_events[0]
    assert api.get("/data/config").json()["event_timeline_end"] == expected_end
    advanced = api.get(f"/advance?time={expected_events[-1]}").json()
    assert [e["time"] for e in advanced["processed_events"]] == expected_events
    assert api.post("/evaluate").json()["condition_at"] == expected_condition
