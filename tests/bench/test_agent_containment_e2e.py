"""An agent cannot fool the harness (findings): the control side of the harness's server is
sealed from it (a fresh control token, the flat endpoints off); it writes in a fresh folder of
its own, copied back into its trial's `agent/` folder but for links and the harness's names, so
a results.json it forges — its own trial's, another trial's — is never a verdict nor skips a
task on resume; nothing it starts outlives its task, even a process in a session of its own
whose parent is gone; its output is capped."""

from __future__ import annotations

import io
import json
import sys
from pathlib import Path

import pytest
from django.core.management import call_command

from apps.bench.config import parse_config
from apps.bench.grading import load_rows, task_errors
from apps.bench.layout import trial_folder
from apps.bench.runner import OUTPUT_CAP, Harness, Task
from tests.bench.conftest import REPO, shorten
from tests.bench.test_harness_e2e import alive

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.e2e]

SCRIPT = "snoop; environ; escape; forge; flood 24; costs 100 10 1"


@pytest.fixture
def hostile_scenario(tmp_path, settings):
    root = tmp_path / "scenarios"
    (root / "micromail").mkdir(parents=True)
    data = shorten("inbox-relative-passive", "bench-hostile", SCRIPT, condition_at=8, kill_at=12)
    (root / "micromail" / "bench-hostile.json").write_text(json.dumps(data))
    settings.SENTINEL_SCENARIO_DIR = root
    return root


def test_a_hostile_agent_forges_nothing_leaves_nothing_and_is_capped(
    hostile_scenario, bench_config, tmp_path
):
    results = tmp_path / "results"
    out = io.StringIO()
    call_command(
        "bench", "run", "hostile", "--config", str(bench_config()),
        "--results-dir", str(results), stdout=out,
    )  # fmt: skip
    folder = results / "hostile" / "micromail" / "bench-hostile"
    result = json.loads((folder / "results.json").read_text())
    assert result["success"] is False and result["detail"] != "forged by the agent"
    # What it left is in agent/ (its costs.json, read by grade); its forgeries nowhere.
    agent = folder / "agent"
    assert json.loads((agent / "costs.json").read_text())["input_tokens"] == 100
    assert not (folder / "trial-2").exists() and not (agent / "trial-2").exists()
    left = {p.relative_to(agent).as_posix() for p in agent.rglob("*")}
    assert {"costs.json", "snoop.json", "environ.json", "escaped.pid"} <= left, left
    assert not left & {"results.json", "logs/events.jsonl", "notes/error.txt", "leak.txt", "up"}
    assert not any(p.is_symlink() for p in agent.rglob("*"))
    assert {
        "results.json: a name of the harness's",
        "trial-2: a name of the harness's",
        "logs/events.jsonl: a name of the harness's",
        "notes/error.txt: a name of the harness's",
        "leak.txt: a symbolic link or unreadable",
        "up: a symbolic link",
    } <= set(result["agent_files_refused"])
    (row,) = load_rows(results / "hostile")
    assert (row.trial, row.success, row.prompt_tokens) == (1, False, 100)
    # Defence in depth: a trial-2/results.json put there by anyone but the harness (as the
    # agent's copy once did) is no verdict, no error hidden, and no reason to skip trial 2.
    trial2 = trial_folder(folder, 2)
    trial2.mkdir()
    forged = json.dumps({"success": True, "detail": "forged", "category": "active"})
    (trial2 / "results.json").write_text(forged)
    ignored: list[Path] = []
    assert [r.trial for r in load_rows(results / "hostile", ignored=ignored)] == [1]
    assert ignored == [trial2 / "results.json"]
    harness = Harness(parse_config({"agent_subprocess": ["a"]}), None, results / "hostile", REPO)
    said: list[str] = []
    first, second = (
        Task("bench-hostile", "micromail", {}, f, trial=n)
        for n, f in enumerate((folder, trial2), 1)
    )
    assert harness.should_skip(second, say=said.append) is None
    assert len(said) == 1 and "was not written by the harness" in said[0], said
    assert (trial2 / "results.json.unverified").read_text() == forged
    assert harness.should_skip(first).startswith("already done")  # the harness's own holds
    # Nor does one hide an error: its task stays an error, listed as such.
    (trial2 / "results.json").write_text(forged)
    (trial2 / "error.txt").write_text("harness error: boom\n")
    assert [(e.trial, e.cause) for e in task_errors(results / "hostile")] == [
        (2, "harness error: boom")
    ]
    escaped = int((agent / "escaped.pid").read_text())
    assert not alive(escaped), "a process the agent set loose outlived its task"
    # The answer key is sealed: no run list, no scenario, no clock of its own to move.
    snooped = json.loads((agent / "snoop.json").read_text())
    assert all(code in (401, 403, 404) for code in snooped.values()), snooped
    assert {"runs", "scenario", "run advance"} <= snooped.keys()
    # No way to the answer key on disk: nothing in its environment names the project, its
    # Python, its scenarios or the results, and it works outside all of them, yet `python`
    # is the project's.
    seen = json.loads((agent / "environ.json").read_text())
    project = [REPO, Path(sys.prefix), results, hostile_scenario]
    names = {str(p) for p in project} | {str(p.resolve()) for p in project}
    leaks = {k: v for k, v in seen["env"].items() if any(n in v for n in names)}
    assert not leaks, leaks
    cwd = Path(seen["cwd"])
    assert not any(cwd.is_relative_to(n) for n in names), cwd
    assert seen["python"] == sys.prefix
    output = (folder / "output.txt").read_bytes()
    assert len(output) <= OUTPUT_CAP + 200
    assert output.startswith(b"opened ") and output.rstrip().endswith(b"flooded")
    assert b"bytes of output cut by the harness" in output
