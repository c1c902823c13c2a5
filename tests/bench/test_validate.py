"""`bench validate` runs the control agents and the cheating strategies on every scenario and
checks the verdicts."""

from __future__ import annotations

import io
import json
import re
from pathlib import Path

import pytest
from django.core.management import call_command

from tests.bench.conftest import shorten

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.e2e]


def validate(*args: str) -> list[str]:
    out = io.StringIO()
    try:
        call_command(
            "bench", "validate", "--speed-factor", "4", "--reaction-window", "2", *args, stdout=out
        )
    finally:  # a failed validation's PROBLEM lines are the diagnosis
        print(out.getvalue())
    return out.getvalue().splitlines()


def test_validate_proves_the_short_scenarios_solvable_and_not_trivially_passable(bench_scenarios):
    lines = validate("--parallel", "10")
    # The cheating strategies earn nothing they should not: act_all passes no active task
    # (bench-active's eval_sql rejects flagging a distractor), fixed_time no active task and
    # quitter nothing, not even the no-op it left (the paper's rule). Passive passes at the
    # deadline are the sleeper's (timely only here: these conditions sit just before it).
    assert re.fullmatch(
        r"bench_validate: scenarios=6 oracle=6/6 early_fail=5/5 never_ok=6/6 sleeper=\d/6 "
        r"act_all=\d/6 act_all_timely=\d/5 fixed_time=\d/6 fixed_time_timely=\d/5 "
        r"quitter=0/6 quitter_timely=0/5 late_ephemeral=0/0 unseen=\d/5 wall_s=[\d.]+ "
        r"clock=virtual",
        lines[-1],
    )
    assert not [line for line in lines if line.startswith("PROBLEM")]
    assert any(line.startswith("quitter (leaves at once): success 0.0% (0/6)") for line in lines)


def test_under_the_original_rule_quitting_passes_the_no_ops(bench_scenarios):
    lines = validate("--parallel", "10", "--filter", "noop", "--noop-rule", "original")
    assert "quitter=1/1" in lines[-1], lines[-1]


def verdicts(lines: list[str]) -> dict[tuple[str, str], bool]:
    """(agent, scenario) → success, read from the kept results folder."""
    root = Path(re.search(r"results -> (\S+)\)", "\n".join(lines)).group(1))
    return {
        (path.parts[-4], path.parts[-2]): json.loads(path.read_text())["success"]
        for path in root.glob("*/*/*/results.json")
    }


def test_virtual_clocks_give_the_verdicts_of_live_clocks_at_speed_4(tmp_path, settings):
    # Two MicroMail scenarios made very short: a passive one and an active one (the oracle acts).
    root = tmp_path / "scenarios" / "micromail"
    root.mkdir(parents=True)
    for new_id, source in (("quick-passive", "sender-absolute-passive"),
                           ("quick-active", "body-keyword-absolute-active")):  # fmt: skip
        # At speed 4 (the clock starts when the agent opens the task): the condition at 10 wall
        # s, the fixed-time contact at half the run (12.5 s), the sleeper's 5 s before its
        # deadline (20 s). A loaded machine only delays an agent, so the one live verdict it can
        # move is the early agent's: its first page and contact get the condition's 10 s (5 s
        # was too few for a fully loaded CI machine).
        data = shorten(source, new_id, "", condition_at=40.0, kill_at=88.0, end=100.0)
        (root / f"{new_id}.json").write_text(json.dumps(data))
    settings.SENTINEL_SCENARIO_DIR = root.parent

    virtual = validate("--keep")
    live = validate("--keep", "--real-time")

    assert virtual[-1].endswith("clock=virtual") and live[-1].endswith("clock=live")
    assert len(verdicts(virtual)) == 14  # seven agents
    on_virtual, on_live = verdicts(virtual), verdicts(live)
    differing = {k: (v, on_live.get(k)) for k, v in on_virtual.items() if on_live.get(k) != v}
    assert not differing, f"(virtual, live) verdicts differ: {differing}"
