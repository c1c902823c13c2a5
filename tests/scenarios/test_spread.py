"""Condition times spread as the paper's: `checkscenarios` prints the targeted scenarios per
100-second bin and fails when one bin holds more than a quarter of them."""

from __future__ import annotations

import io
import json

import pytest
from django.core.management import CommandError, call_command

from apps.scenarios.format import parse_scenario
from apps.scenarios.spread import MAX_BIN_SHARE, condition_spread
from events.timing import MAX_CONDITION_AT, MAX_SPEED_FACTOR
from tests.conftest import OUR_SCENARIOS


def checkscenarios(directory) -> list[str]:
    out = io.StringIO()
    call_command("checkscenarios", str(directory), stdout=out)
    return out.getvalue().splitlines()


@pytest.mark.slow
def test_our_condition_times_fill_every_100_second_bin_below_a_quarter():
    lines = checkscenarios(OUR_SCENARIOS)
    bins = [line for line in lines if line.startswith("  [")]
    assert [line.split(":")[0].strip() for line in bins] == [
        "[  0, 100) s",
        "[100, 200) s",
        "[200, 300) s",
        "[300, 400) s",
        "[400, 500) s",
        "[500, 600] s",
    ]
    shares = [float(line.split("(")[1].split("%")[0]) for line in bins]
    assert all(0 < share <= 100 * MAX_BIN_SHARE for share in shares), bins
    assert lines[-1].startswith("condition_at spread: ok: no bin above 25 %")


@pytest.mark.slow
def test_bunched_condition_times_fail_naming_the_crowded_bin(tmp_path):
    root = tmp_path / "scenarios"
    for path in OUR_SCENARIOS.glob("*/*.json"):
        data = json.loads(path.read_text())
        if data.get("condition_at") is not None:
            # Only the claims move (the format does not see events); an ephemeral window moves
            # whole, so it still ends after it begins.
            if data.get("condition_until") is not None:
                data["condition_until"] += 250.0 - data["condition_at"]
            data["condition_at"] = 250.0
        (root / path.parent.name).mkdir(parents=True, exist_ok=True)
        (root / path.parent.name / path.name).write_text(json.dumps(data))
    out = io.StringIO()
    with pytest.raises(CommandError, match="condition times are bunched"):
        call_command("checkscenarios", str(root), stdout=out)
    assert "condition_at spread: FAIL: above 25 % in [200, 300) s 100.0 %" in out.getvalue()


def scenario_at(condition_at: float | None, *, kill_at: float = 630.0):
    return parse_scenario(
        {
            "id": f"at-{condition_at}",
            "environment": "tally",
            "prompt": "p",
            "start_page": "HOST_ADDRESS/tally",
            "condition_at": condition_at,
            "event_timeline_end": 720.0,
            "kill_at": kill_at,
            "events": [],
            "eval_sql": "SELECT 1",
            "taxonomy": {},
        }
    )


def test_600_s_falls_in_the_last_bin_and_no_ops_are_not_counted():
    spread = condition_spread(
        [scenario_at(t) for t in (10.0, 99.9, 100.0, 600.0)] + [scenario_at(None)]
    )
    assert spread.targeted == 4
    assert [b.count for b in spread.bins] == [2, 1, 0, 0, 0, 1]
    assert spread.bins[-1].label == "[500, 600] s"


def test_a_small_folder_is_printed_but_not_judged():
    spread = condition_spread([scenario_at(250.0)] * 3)
    assert not spread.judged and spread.crowded == ()
    assert [b.share for b in spread.bins][2] == 1.0


def test_a_report_in_the_last_5_wall_seconds_before_the_deadline_is_never_timely():
    # At speed ≤ MAX_SPEED_FACTOR the harness deadline is MAX_CONDITION_AT / sf + the reaction
    # window; a contact 5 wall seconds before it (the sleeper control agent's) is within the
    # window only for a condition at or after MAX_CONDITION_AT - 5 * sf: 580 s at speed 4.
    latest = max(
        s.condition_at
        for s in (
            parse_scenario(json.loads(p.read_text()))
            for p in OUR_SCENARIOS.glob("*/*.json")
            if p.name != "dev.json"
        )
        if s.condition_at is not None
    )
    assert latest < MAX_CONDITION_AT - 5 * MAX_SPEED_FACTOR
