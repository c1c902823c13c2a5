"""`bench validate` is a measurement, so it must not move with the machine's load: with both
cores kept busy by other processes it gives the same counts three times in a row (a control
agent's own timeout is an error, run again, never a verdict), and it exits non-zero when a
control agent's verdict differs from what the scenario requires."""

from __future__ import annotations

import io
import json
import os
import re
import subprocess
import sys
import time

import pytest
from django.core.management import CommandError, call_command

from tests.bench.conftest import shorten

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.e2e]

BURN = "while True: pass"


def idle_cores(seconds: float = 1.0) -> float:
    """How many cores' worth of CPU nothing else is using now (from /proc/stat)."""

    def ticks() -> tuple[int, int]:
        with open("/proc/stat") as stat:
            fields = [int(n) for n in stat.readline().split()[1:]]
        return sum(fields), fields[3] + fields[4]  # all, idle + iowait

    total, idle = ticks()
    time.sleep(seconds)
    total_after, idle_after = ticks()
    return (os.cpu_count() or 1) * (idle_after - idle) / max(1, total_after - total)


def validate(*args: str) -> str:
    out = io.StringIO()
    try:
        call_command(
            "bench", "validate", "--speed-factor", "4", "--reaction-window", "2", *args, stdout=out
        )
    finally:
        print(out.getvalue())  # shown when it fails: which verdict differed, which task erred
    return out.getvalue()


def counts(line: str) -> str:
    """The last line without its wall time."""
    assert line.startswith("bench_validate: "), line
    return re.sub(r" wall_s=[\d.]+", "", line)


def test_validate_gives_the_same_counts_three_times_on_a_busy_machine(bench_scenarios):
    # A passive, an active and a no-op: each kind of verdict, three times over, with every
    # core kept busy: by a burner for each core that nothing else uses. Inside the whole suite
    # its other processes already keep the cores busy, and burners there would only take their
    # CPU (alone, the burners were most of this test's CPU, and slowed the suite by as much).
    for extra in ("bench-early", "bench-hung", "bench-linger"):
        (bench_scenarios / "micromail" / f"{extra}.json").unlink()
    idle = idle_cores()
    burners = [subprocess.Popen([sys.executable, "-c", BURN]) for _ in range(round(idle))]
    print(f"{idle:.1f} idle cores: {len(burners)} burners")
    try:
        lines = [counts(validate("--parallel", "10").splitlines()[-1]) for _ in range(3)]
    finally:
        for burner in burners:
            burner.kill()
            burner.wait()
    print("\n".join(lines))
    assert lines[0] == lines[1] == lines[2]
    assert lines[0].startswith("bench_validate: scenarios=3 oracle=3/3 early_fail=2/2 never_ok=3/3")


def test_a_control_verdict_that_differs_from_the_scenario_fails_validation(tmp_path, settings):
    # A no-op whose eval_sql can never hold: even the agent that rightly stays silent fails.
    root = tmp_path / "scenarios" / "micromail"
    root.mkdir(parents=True)
    data = shorten("sender-absolute-noop", "unpassable-noop", "")
    data["eval_sql"] = "SELECT 0"
    (root / "unpassable-noop.json").write_text(json.dumps(data))
    settings.SENTINEL_SCENARIO_DIR = root.parent
    out = io.StringIO()
    with pytest.raises(CommandError) as error:
        try:
            call_command("bench", "validate", "--speed-factor", "4", stdout=out)
        finally:
            print(out.getvalue())
    assert error.value.returncode == 1
    assert "PROBLEM: oracle failed unpassable-noop" in out.getvalue()
    assert "PROBLEM: never failed unpassable-noop" in out.getvalue()
    assert "validation failed: 2 problem(s), 0 harness error(s)" in str(error.value)


def test_validating_no_scenario_is_no_proof(tmp_path, settings):
    (tmp_path / "scenarios").mkdir()
    settings.SENTINEL_SCENARIO_DIR = tmp_path / "scenarios"
    with pytest.raises(CommandError, match=r"preflight: server .*: no scenario to run") as error:
        call_command("bench", "validate", stdout=io.StringIO())
    assert error.value.returncode == 2
