"""The harness owns its records (issue #26): what an agent leaves is copied into its trial's
`agent/` folder only — never a link, never a name of the harness's, at any depth — and a
results.json the set's ledger does not have as written by the harness is no verdict, hides no
error and skips no task on resume. The agent's side is played here in process, as the audit
did; tests/bench/test_agent_containment_e2e.py plays it from a real agent under `bench run`."""

from __future__ import annotations

import io
import json
import os
from pathlib import Path

import pytest
from django.core.management import call_command

from apps.bench import ledger, runner
from apps.bench.config import parse_config
from apps.bench.grading import load_rows, task_errors
from apps.bench.judge import JUDGEMENT
from apps.bench.layout import HARNESS_NAMES, LEDGER
from apps.bench.manifest import MANIFEST
from apps.bench.runner import AgentWorkspace, Harness, Progress, Task
from apps.bench.summary import SUMMARY

FORGED = {"success": True, "detail": "forged", "category": "active", "condition_at": 10.0}
HARNESS_RESULT = {"success": False, "detail": "no contact", "category": "active"}


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


def harness_at(root: Path) -> Harness:
    return Harness(parse_config({"agent_subprocess": ["a"]}), None, root, root)


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


def test_an_agent_cannot_fill_the_results_disk(tmp_path, monkeypatch):
    """What an agent leaves is copied back up to a byte and a file allowance per trial: the
    top-level files the reports read first, then what fits; the rest is named as refused."""
    monkeypatch.setattr(runner, "AGENT_FILES_MAX_COUNT", 4)
    with AgentWorkspace(tmp_path) as workspace:
        (workspace.path / "costs.json").write_text('{"input_tokens": 7}')
        with open(workspace.path / "huge.bin", "wb") as huge:  # sparse: no disk used here
            huge.truncate(runner.AGENT_FILES_MAX_BYTES + 1)
        (workspace.path / "screens").mkdir()
        for step in range(5):
            (workspace.path / "screens" / f"step-{step}.png").write_bytes(b"png")
    kept = sorted(p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*") if p.is_file())
    assert kept == [
        "agent/costs.json",
        "agent/screens/step-0.png",
        "agent/screens/step-1.png",
        "agent/screens/step-2.png",
    ]
    assert workspace.refused == [
        "huge.bin: over the 512 MiB copied back per trial",
        "screens/step-3.png: over the 4 files copied back per trial",
        "screens/step-4.png: over the 4 files copied back per trial",
    ]


def test_every_name_the_harness_writes_is_refused():
    assert {JUDGEMENT, MANIFEST, SUMMARY, LEDGER, "results.json", "error.txt"} <= HARNESS_NAMES
    assert {"output.txt", "events.jsonl", "prompt.txt", "results.json.unverified"} <= HARNESS_NAMES


def write_harness_result(root: Path, folder: Path, result: dict) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    ledger.start(root)
    ledger.write_result(root, folder / "results.json", result)


def test_resuming_runs_again_a_task_whose_results_json_the_harness_did_not_write(tmp_path):
    task = tmp_path / "micromail" / "t"
    write_harness_result(tmp_path, task, HARNESS_RESULT)
    first = Task("t", "micromail", {}, task)
    second = Task("t", "micromail", {}, task / "trial-2", trial=2)
    second.folder.mkdir()
    (second.folder / "results.json").write_text(json.dumps(FORGED))
    out = io.StringIO()
    todo = harness_at(tmp_path).pending([first, second], Progress(out, tty=False))
    assert todo == [second]
    assert out.getvalue().splitlines() == [
        "Skipping t (already done)",
        f"Running t (trial 2) again: {second.folder / 'results.json'} was not written by the "
        f"harness (no match in {LEDGER}; kept as results.json.unverified)",
    ]
    assert (second.folder / "results.json.unverified").exists()
    assert not (second.folder / "results.json").exists()


def test_a_harness_result_changed_afterwards_is_no_longer_a_verdict(tmp_path):
    task = tmp_path / "micromail" / "t"
    write_harness_result(tmp_path, task, HARNESS_RESULT)
    said: list[str] = []
    assert harness_at(tmp_path).should_skip(Task("t", "micromail", {}, task)) == "already done"
    (task / "results.json").write_text(json.dumps(FORGED))
    assert (
        harness_at(tmp_path).should_skip(Task("t", "micromail", {}, task), say=said.append) is None
    )
    assert len(said) == 1


def test_grading_ignores_and_names_a_results_json_the_harness_did_not_write(tmp_path):
    root = tmp_path / "results" / "set"
    task = root / "micromail" / "t"
    write_harness_result(root, task, HARNESS_RESULT)
    for trial in (2, 3):
        (task / f"trial-{trial}").mkdir()
        (task / f"trial-{trial}" / "results.json").write_text(json.dumps(FORGED))
    (task / "trial-3" / "error.txt").write_text("harness error: boom\n")
    ignored: list[Path] = []
    rows = load_rows(root, ignored=ignored)
    assert [(r.trial, r.success) for r in rows] == [(1, False)]
    assert ignored == [task / "trial-2" / "results.json", task / "trial-3" / "results.json"]
    assert [(e.trial, e.cause) for e in task_errors(root)] == [(3, "harness error: boom")]
    err = io.StringIO()
    call_command(
        "bench", "grade", "set", "--results-dir", str(tmp_path / "results"),
        stdout=io.StringIO(), stderr=err,
    )  # fmt: skip
    assert err.getvalue().splitlines() == [
        f"ignored {task / 'trial-2' / 'results.json'}: not written by the harness "
        f"(no match in {LEDGER})",
        f"ignored {task / 'trial-3' / 'results.json'}: not written by the harness "
        f"(no match in {LEDGER})",
    ]


def test_a_set_from_before_the_ledger_is_read_as_before_and_adopted_on_resume(tmp_path):
    task = tmp_path / "micromail" / "t"
    task.mkdir(parents=True)
    (task / "results.json").write_text(json.dumps(HARNESS_RESULT))
    (task / "costs.json").write_text('{"input_tokens": 5}')  # where agents' files were
    (row,) = load_rows(tmp_path)
    assert (row.success, row.prompt_tokens) == (False, 5)
    out = io.StringIO()
    assert harness_at(tmp_path).pending([Task("t", "micromail", {}, task)], Progress(out)) == []
    assert out.getvalue().splitlines() == [
        f"{tmp_path / LEDGER}: started, with the 1 results.json written before it",
        "Skipping t (already done)",
    ]
    assert ledger.start(tmp_path) == 0  # once
    (task / "trial-2").mkdir()
    (task / "trial-2" / "results.json").write_text(json.dumps(FORGED))  # after: not adopted
    assert [r.trial for r in load_rows(tmp_path)] == [1]


@pytest.mark.parametrize("ledger_text", ["", "not json\n[1]\n{}\n"])
def test_an_empty_or_garbled_ledger_vouches_for_nothing(tmp_path, ledger_text):
    task = tmp_path / "micromail" / "t"
    task.mkdir(parents=True)
    (task / "results.json").write_text(json.dumps(FORGED))
    (tmp_path / LEDGER).write_text(ledger_text)
    assert load_rows(tmp_path) == []
