"""The story of a benchmark: a scripted agent runs six short MicroMail tasks at speed 4, in
parallel, through the real embedded server; the results tree, the grade table and the CSV say
what happened; a hung agent and its child are killed at the deadline; a second run resumes."""

from __future__ import annotations

import csv
import io
import json
import os

import pytest
from django.core.management import call_command

from apps.bench.models import BenchmarkRun, TaskResult

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.e2e]


def alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    # A zombie is dead for our purpose (killed, waiting to be reaped by its parent).
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().split(")")[1].split()[0] != "Z"
    except FileNotFoundError:
        return False


def bench(*args) -> str:
    out = io.StringIO()
    call_command("bench", *args, stdout=out)
    return out.getvalue()


def test_a_benchmark_run_with_a_scripted_agent(bench_scenarios, bench_config, tmp_path):
    # A reaction window of 14 s: the no-op agent must outstay its run's end (15 s) and exit
    # before its deadline, which counts from its launch. A loaded machine's Python start-up
    # spent the 4 s there once were, and on a slow machine under CI the 8 s after them.
    config = bench_config(reaction_window=14)
    results = tmp_path / "results"
    log = bench("run", "story", "--config", str(config), "--results-dir", str(results))
    print(log)
    assert "Found 6 tasks" in log
    assert "ran=6 passed=4 failed=2 errors=0" in log

    tree = results / "story" / "micromail"
    outcome = {d.name: json.loads((d / "results.json").read_text()) for d in tree.iterdir()}
    assert {k: v["success"] for k, v in outcome.items()} == {
        "bench-passive": True,
        "bench-active": True,
        "bench-noop": True,
        "bench-early": False,
        "bench-hung": False,
        "bench-linger": True,
    }
    passive = outcome["bench-passive"]
    for field in (
        "success",
        "detail",
        "evaluation_time",
        "condition_at",
        "contact_get_time",
        "contact_post_time",
        "contact_message",
        "run",
        "category",
        "reaction_time",
        "views",
        "actions",
    ):
        assert field in passive
    assert passive["condition_at"] == 10.0  # authored 40 s at speed 4, in wall seconds
    assert 0 <= passive["reaction_time"] <= passive["deadline_s"]
    assert passive["category"] == "passive-absolute"
    assert passive["contact_message"] == "done"
    assert passive["views"] >= 2
    assert outcome["bench-active"]["category"] == "active-absolute"
    assert outcome["bench-active"]["actions"] == 2  # opens the mail, flags it
    assert outcome["bench-noop"]["category"] == "noop"
    assert outcome["bench-noop"]["contact_get_time"] is None
    assert "before the condition held" in outcome["bench-early"]["detail"]
    for name in outcome:
        folder = tree / name
        assert (folder / "output.txt").stat().st_size > 0
        header, *events = map(json.loads, (folder / "events.jsonl").read_text().splitlines())
        assert header["format"] == "sentinel-run/1"  # export_run's format: import_run reads it
        assert [e["seq"] for e in events] == list(range(1, len(events) + 1))
        assert not (folder / "error.txt").exists()
    assert "contacted" in (tree / "bench-active" / "output.txt").read_text()

    # The hung agent (and the child it spawned) were killed at the deadline: 20/4 + 14 = 19 s.
    hung = outcome["bench-hung"]
    assert hung["agent_killed"] is True
    assert hung["deadline_s"] == 19.0
    assert hung["agent_wall_s"] >= 18.0  # not killed before its deadline (how long after: load)
    assert "the agent never visited /contact" in hung["detail"]
    for pidfile in ("agent.pid", "child.pid"):
        assert not alive(int((tree / "bench-hung" / "agent" / pidfile).read_text()))
    # An agent that exits by itself still has its process group killed: no child survives.
    assert outcome["bench-noop"]["agent_killed"] is False
    assert not alive(int((tree / "bench-noop" / "agent" / "child.pid").read_text()))
    # An agent that contacted but lingers gets the grace period (5 s), then is killed.
    linger = outcome["bench-linger"]
    assert linger["agent_killed"] is True
    assert linger["agent_wall_s"] >= 23.0  # the 19 s deadline, then the whole 5 s of grace

    # The database mirrors the tree, with links to the graded runs.
    benchmark = BenchmarkRun.objects.get(name="story")
    assert benchmark.speed_factor == 4.0 and benchmark.finished_at is not None
    rows = {t.scenario_id: t for t in TaskResult.objects.filter(benchmark=benchmark)}
    assert (
        rows["bench-active"].success is True
        and rows["bench-active"].run_id == outcome["bench-active"]["run"]
    )
    assert rows["bench-active"].cost_usd == pytest.approx((20000 * 2.0 + 1000 * 10.0) / 1e6)
    assert rows["bench-early"].category == "passive-relative"

    # A second run skips every finished task.
    again = bench("run", "story", "--config", str(config), "--results-dir", str(results))
    assert again.count("(already done)") == 6
    assert "ran=0" in again

    # Grade: the upstream table and summary, then the paper's breakdown.
    table = bench("grade", "story", "--results-dir", str(results), "--config", str(config))
    print(table)
    header = table.splitlines()[0]
    assert [c.strip() for c in header.split("|")] == [
        "name",
        "evaluation_time",
        "success",
        "stop_time",
        "condition_at",
        "reaction_time",
        "prompt_tokens",
        "completion_tokens",
        "tool_calls",
    ]
    active_line = next(line for line in table.splitlines() if line.startswith("bench-active "))
    cells = [c.strip() for c in active_line.split("|")]
    assert cells[2] == "True" and cells[4] == "10.00" and cells[6:] == ["20000", "1000", "6"]
    assert "Total Tasks: 6" in table
    assert "Task Success Rate: 66.7% (4/6)" in table
    assert "noop 100.0% (1/1) | passive 50.0% (2/4) | active 100.0% (1/1)" in table
    assert "absolute 100.0% (3/3) | relative 0.0% (0/2)" in table
    assert "Cost (USD): median $0.0180, mean $0.0221 (n=4)" in table
    assert "Tool Calls: mean 3.2, median 3.0" in table

    text = bench("grade", "story", "--csv", "--results-dir", str(results), "--config", str(config))
    lines = text.splitlines()
    blank = lines.index("")
    data = list(csv.DictReader(lines[:blank]))
    assert len(data) == 6
    passive_row = next(r for r in data if r["name"] == "bench-passive")
    assert passive_row["success"] == "True" and passive_row["prompt_tokens"] == "10000"
    summary = dict(csv.reader(lines[blank + 1 :]))
    assert summary["Total Tasks"] == "6" and summary["Successes"] == "4"
    assert summary["Task Success Rate"] == "0.6667"
    assert summary["Average Tool Calls"] == "3.2"
    assert summary["Success Rate noop"] == "1.0000"


def test_a_bad_config_is_one_line_and_exit_2(tmp_path, capsys):
    from django.core.management import CommandError

    config = tmp_path / "eval_config.yaml"
    config.write_text("speed_factor: 9\nagent_subprocess: [echo]\n")
    with pytest.raises(CommandError) as error:
        call_command("bench", "run", "x", "--config", str(config))
    assert error.value.returncode == 2
    assert "speed_factor" in str(error.value) and "\n" not in str(error.value)
    config.write_text("server_url: http://x\n")
    with pytest.raises(CommandError, match="agent_subprocess: is required") as error:
        call_command("bench", "run", "x", "--config", str(config))
    assert error.value.returncode == 2
