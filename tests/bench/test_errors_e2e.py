"""An agent that crashes before it opens its task is the setup's problem, not the agent's
failing: the task is an `error` — no results.json, not in any rate, listed with its cause,
`bench run` exits 1, a rerun skips it saying why, and `--retry-errors` runs it again. A no-op
whose agent never started is never a pass. Real embedded server, real agent subprocesses."""

from __future__ import annotations

import io
import sys

import pytest
import yaml
from django.core.management import CommandError, call_command

from apps.bench.models import TaskResult

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.e2e]

CRASH = [sys.executable, "-c", "raise SystemExit('my_agent: cannot import my_model')"]
TASKS = ("--task", "bench-noop", "--task", "bench-passive")


def bench(*args: str) -> tuple[str, CommandError | None]:
    out = io.StringIO()
    try:
        call_command("bench", *args, stdout=out)
    except CommandError as error:
        return out.getvalue(), error
    return out.getvalue(), None


def test_a_crash_before_the_task_is_an_error_never_cached_and_retried(
    bench_scenarios, bench_config, tmp_path
):
    config = bench_config()
    crashing = tmp_path / "crashing.yaml"
    crashing.write_text(
        yaml.safe_dump({**yaml.safe_load(config.read_text()), "agent_subprocess": CRASH})
    )
    results = tmp_path / "results"
    where = ("--results-dir", str(results))

    log, error = bench("run", "setup", "--config", str(crashing), *TASKS, *where)
    print(log)
    assert error is not None and error.returncode == 1
    assert "2 task(s) are errors" in str(error) and "--retry-errors" in str(error)
    assert "ran=2 passed=0 failed=0 errors=2" in log
    cause = "the agent never opened its task page (it exited with code 1)"
    assert f"micromail/bench-noop: {cause}" in log  # listed with its cause
    assert "my_agent: cannot import my_model" in log  # and the agent's own last words
    for name in ("bench-noop", "bench-passive"):
        folder = results / "setup" / "micromail" / name
        assert not (folder / "results.json").exists()  # never cached as a result
        assert (folder / "error.txt").read_text().splitlines()[0] == cause

    # The database keeps them as errors, without a success either way.
    mirrored = TaskResult.objects.get(benchmark__name="setup", scenario_id="bench-noop")
    assert mirrored.success is None and mirrored.error.startswith(cause)

    # Grading counts them apart: no rate includes them.
    table, error = bench("grade", "setup", *where)
    assert error is None
    assert "Total Tasks: 0" in table and "errors (not graded, not in any rate): 2" in table

    # A rerun does not run them again by itself, says why, and still exits non-zero.
    log, error = bench("run", "setup", "--config", str(config), *TASKS, *where)
    assert error is not None and error.returncode == 1
    assert f"Skipping bench-noop (previous error: {cause}; --retry-errors runs it again)" in log

    # Fixed (the working agent) and retried: graded now, exit 0.
    log, error = bench("run", "setup", "--config", str(config), *TASKS, "--retry-errors", *where)
    print(log)
    assert error is None, error
    assert "ran=2 passed=2 failed=0 errors=0" in log
    for name in ("bench-noop", "bench-passive"):
        folder = results / "setup" / "micromail" / name
        assert (folder / "results.json").exists() and not (folder / "error.txt").exists()
    table, _ = bench("grade", "setup", *where)
    assert "Task Success Rate: 100.0% (2/2)" in table and "errors (not graded" not in table
