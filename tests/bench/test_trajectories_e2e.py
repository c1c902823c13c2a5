"""`bench export-trajectories` on a real result set (the scripted agent under the harness,
through the embedded server), run as the README writes it, loaded back with `json` alone and
checked against every task's results.json and events.jsonl."""

from __future__ import annotations

import io
import json

import pytest
from django.core.management import call_command

from tests.first_hour.test_readme_harness import code_blocks, command_line, readme_section

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.e2e]

TASKS = ("bench-passive", "bench-active", "bench-early")


def bench(*args) -> str:
    out = io.StringIO()
    call_command("bench", *args, stdout=out)
    return out.getvalue()


def readme_export(results_dir, out) -> list[str]:
    """The README's command line, on this test's result set and file."""
    blocks = code_blocks(readme_section("The task timeline"))
    code = next(
        code for lang, code, _ in blocks if lang == "bash" and "export-trajectories" in code
    )
    argv = command_line(code, ".venv/bin/python manage.py bench export-trajectories")
    assert argv[3:] == [
        "export-trajectories",
        "results/nightly",
        "--format",
        "jsonl",
        "--out",
        "nightly.jsonl",
    ]
    return [argv[3], str(results_dir / "nightly"), *argv[5:8], str(out)]  # fmt: skip


def test_exported_trajectories_match_every_tasks_results(bench_scenarios, bench_config, tmp_path):
    results = tmp_path / "results"
    tasks = [arg for task in TASKS for arg in ("--task", task)]
    log = bench(
        "run", "nightly", "--config", str(bench_config()), "--results-dir", str(results), *tasks
    )
    assert "errors=0" in log, log

    out = tmp_path / "nightly.jsonl"
    call_command("bench", *readme_export(results, out))
    records = [json.loads(line) for line in out.read_text().splitlines()]

    folders = sorted((results / "nightly" / "micromail").iterdir())
    assert sorted(r["task"] for r in records) == [f.name for f in folders] == sorted(TASKS)
    for folder in folders:
        result = json.loads((folder / "results.json").read_text())
        (record,) = [r for r in records if r["task"] == folder.name]
        assert record["format"] == "sentinel-trajectory/1"
        assert (record["result_set"], record["environment"]) == ("nightly", "micromail")
        reward = record["reward"]
        assert reward["success"] == result["success"]
        assert reward["detail"] == result["detail"]
        assert reward["reaction_time"] == pytest.approx(result["reaction_time"])
        assert reward["contact_message"] == result["contact_message"]
        header, *log = [
            json.loads(line) for line in (folder / "events.jsonl").read_text().splitlines()
        ]
        scenario = header["run"]["scenario"]
        assert record["prompt"] == (folder / "prompt.txt").read_text()
        assert record["scenario"]["condition_at"] == scenario["condition_at"]
        # No transcript (a custom agent that writes none): the steps are its logged visits,
        # actions and contact, in order, on the run's clock.
        agent_entries = [
            e for e in log
            if e["kind"] in ("view", "action") or e["type"] in ("contact_get", "contact_post")
        ]  # fmt: skip
        assert record["steps_from"] == "log"
        assert [s["sim_time"] for s in record["steps"]] == [e["at"] for e in agent_entries]
        assert [s["action"]["tool"] for s in record["steps"]] == [e["type"] for e in agent_entries]
        fired = [e for e in log if e["kind"] == "scenario"]
        assert [e["seq"] for e in record["events"]] == [e["seq"] for e in fired]
        triggers = [e for e in record["events"] if e["role"] == "trigger"]
        assert [e["sim_time"] for e in triggers] == [
            e["at"] for e in fired if e["at"] == scenario["condition_at"]
        ]
        # Targeted tasks all: the trigger fired, but where the agent reported before it came.
        assert bool(triggers) == (folder.name != "bench-early")
    early = next(r for r in records if r["task"] == "bench-early")
    assert early["reward"]["success"] is False and early["reward"]["timely"] is False
