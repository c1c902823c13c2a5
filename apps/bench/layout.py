"""A task's folder in a result set: the names of its files, where a trial keeps them, and why an
errored task erred. Light on purpose: grading, the reports and the admin's pages read result sets
without loading the harness that writes them (its HTTP client and config loader)."""

from __future__ import annotations

from pathlib import Path

RESULTS, ERROR, OUTPUT, EVENTS, COSTS = (
    "results.json",
    "error.txt",
    "output.txt",
    "events.jsonl",
    "costs.json",
)


class BenchError(Exception):
    """A problem the user can fix (bad selection, missing results): one line, exit 2."""


def trial_folder(task_folder: Path, trial: int) -> Path:
    """Where trial `trial` of a task keeps its files (trial 1: the task's own folder)."""
    return task_folder if trial == 1 else task_folder / f"trial-{trial}"


def error_cause_of(folder: Path) -> str:
    """The first line of a task's error.txt: why it is an error."""
    try:
        with open(folder / ERROR, encoding="utf-8", errors="replace") as fh:
            return fh.readline().strip()
    except OSError:
        return ""
