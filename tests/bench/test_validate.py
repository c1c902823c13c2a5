"""`bench validate` runs the four control agents on every scenario and checks the verdicts."""

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
    call_command(
        "bench", "validate", "--speed-factor", "4", "--reaction-window", "2", *args, stdout=out
    )
    print(out.getvalue())
    return out.getvalue().splitlines()


def test_validate_proves_the_short_scenarios_solvable_and_not_trivially_passable(bench_scenarios):
    lines = validate("--parallel", "10")
    assert re.fullmatch(
        r"bench_validate: scenarios=6 oracle=6/6 early_fail=5/5 never_ok=6/6 sleeper=\d/6 "
        r"unseen=\d/5 "
        r"wall_s=[\d.]+ clock=virtual",
        lines[-1],
    )


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
        # At speed 4 (the clock starts when the agent opens the task): the condition at 2 wall
        # s, the sleeper's contact 5 s before its deadline at about 7 s. Every agent acts seconds
        # away from the condition, so a loaded machine's delays cannot move a live verdict.
        data = shorten(source, new_id, "", condition_at=8.0, kill_at=40.0, end=48.0)
        (root / f"{new_id}.json").write_text(json.dumps(data))
    settings.SENTINEL_SCENARIO_DIR = root.parent

    virtual = validate("--keep")
    live = validate("--keep", "--real-time")

    assert virtual[-1].endswith("clock=virtual") and live[-1].endswith("clock=live")
    assert len(verdicts(virtual)) == 8
    assert verdicts(virtual) == verdicts(live)
