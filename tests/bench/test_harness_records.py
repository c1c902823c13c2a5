"""The harness owns its records (issue #26): what an agent leaves is copied into its trial's
`agent/` folder only — never a link, never a name of the harness's, at any depth. The agent's
side is played here in process, as the audit did; tests/bench/test_agent_containment_e2e.py
plays it from a real agent under `bench run`."""

from __future__ import annotations

import json
import os

from apps.bench.grading import load_rows
from apps.bench.judge import JUDGEMENT
from apps.bench.layout import HARNESS_NAMES
from apps.bench.manifest import MANIFEST
from apps.bench.runner import AgentWorkspace
from apps.bench.summary import SUMMARY

FORGED = {"success": True, "detail": "forged", "category": "active", "condition_at": 10.0}


def hostile_agent(workspace: AgentWorkspace) -> None:
    """What the audit's agent of trial 1 wrote in its own folder, and what any agent keeps."""
    here = workspace.path
    (here / "costs.json").write_text('{"input_tokens": 7}')
    (here / "transcript").mkdir()
    (here / "transcript" / "step-001.jpg").write_bytes(b"\xff\xd8 a screenshot")
    (here / "transcript.jsonl").write_text('{"step": 1}\n')
    (here / "results.json").write_text(json.dumps(FORGED))
    (here / "trial-2").mkdir()
    (here / "trial-2" / "results.json").write_text(json.dumps(FORGED))
    (here / "trial-2" / "costs.json").write_text('{"input_tokens": 1}')
    (here / "deep" / "er").mkdir(parents=True)
    (here / "deep" / "er" / "events.jsonl").write_text("{}\n")
    (here / "deep" / "summary.json").write_text("{}")
    (here / "prompt.txt").write_text("its own prompt")  # over the harness's
    (here / "leak.txt").symlink_to("/etc/hostname")
    (here / "up").symlink_to("..")
    os.mkfifo(here / "pipe")


def test_an_agents_files_go_to_agent_and_its_forgeries_nowhere(tmp_path):
    task = tmp_path / "micromail" / "some-task"
    task.mkdir(parents=True)
    with AgentWorkspace(task) as workspace:
        workspace.place("prompt.txt", "the harness's prompt")
        hostile_agent(workspace)
    # Nothing but agent/ in the trial's folder: no trial-2, no results.json.
    assert sorted(p.name for p in task.iterdir()) == ["agent"]
    kept = {p.relative_to(task).as_posix() for p in task.rglob("*") if p.is_file()}
    assert kept == {"agent/costs.json", "agent/transcript.jsonl", "agent/transcript/step-001.jpg"}
    assert (task / "agent" / "transcript" / "step-001.jpg").read_bytes() == b"\xff\xd8 a screenshot"
    assert sorted(workspace.refused) == [
        "deep/er/events.jsonl: a name of the harness's",
        "deep/summary.json: a name of the harness's",
        "leak.txt: a symbolic link or unreadable",
        "pipe: not a regular file",
        "results.json: a name of the harness's",
        "trial-2: a name of the harness's",
        "up: a symbolic link",
    ]  # the harness's own prompt.txt is not the agent's: neither kept nor listed
    assert load_rows(tmp_path) == []  # the audit's forged trial 2: gone
    assert not workspace.root.exists()


def test_a_task_run_again_keeps_only_its_last_agents_files(tmp_path):
    with AgentWorkspace(tmp_path) as workspace:
        (workspace.path / "old.txt").write_text("first attempt")
    with AgentWorkspace(tmp_path) as workspace:
        (workspace.path / "new.txt").write_text("second attempt")
    assert [p.name for p in (tmp_path / "agent").iterdir()] == ["new.txt"]


def test_every_name_the_harness_writes_is_refused():
    assert {JUDGEMENT, MANIFEST, SUMMARY, "results.json", "error.txt"} <= HARNESS_NAMES
    assert {"output.txt", "events.jsonl", "prompt.txt"} <= HARNESS_NAMES
