"""A task's folder in a result set: the names of its files, where a trial keeps them, and why an
errored task erred. Light on purpose: grading, the reports and the admin's pages read result sets
without loading the harness that writes them (its HTTP client and config loader)."""

from __future__ import annotations

from pathlib import Path

RESULTS, ERROR, OUTPUT, EVENTS, COSTS, PROMPT = (
    "results.json",
    "error.txt",
    "output.txt",
    "events.jsonl",
    "costs.json",
    "prompt.txt",
)
# The sub-folder of a trial's folder holding what its agent left in its own folder (costs.json,
# transcript.jsonl, screenshots): everything else in a trial's folder is the harness's.
AGENT = "agent"
LEDGER = "harness-records.jsonl"  # at the top of a result set: what the harness wrote (ledger.py)
UNVERIFIED = RESULTS + ".unverified"  # a results.json the harness did not write, set aside
# Every name the harness writes or reads as its own, in a trial's folder or at the top of a
# result set (judge.JUDGEMENT, manifest.MANIFEST and summary.SUMMARY among them): an agent's
# file or folder of one of these names, or named like a trial's folder, is never copied back,
# at whatever depth it put it (runner.AgentWorkspace).
HARNESS_NAMES = frozenset(
    {RESULTS, ERROR, OUTPUT, EVENTS, PROMPT, LEDGER, UNVERIFIED, RESULTS + ".tmp"}
    | {"judgement.json", "manifest.json", "summary.json"}
)
TRIAL_PREFIX = "trial-"


class BenchError(Exception):
    """A problem the user can fix (bad selection, missing results): one line, exit 2."""


def trial_folder(task_folder: Path, trial: int) -> Path:
    """Where trial `trial` of a task keeps its files (trial 1: the task's own folder)."""
    return task_folder if trial == 1 else task_folder / f"{TRIAL_PREFIX}{trial}"


def agent_files(folder: Path) -> Path:
    """Where a trial's agent files are: its `agent/` folder; in a result set written before
    there was one (or by the original harness), the trial's folder itself."""
    copied = folder / AGENT
    return copied if copied.is_dir() else folder


def error_cause_of(folder: Path) -> str:
    """The first line of a task's error.txt: why it is an error."""
    try:
        with open(folder / ERROR, encoding="utf-8", errors="replace") as fh:
            return fh.readline().strip()
    except OSError:
        return ""
