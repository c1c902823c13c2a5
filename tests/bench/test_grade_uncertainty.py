"""`bench grade` with uncertainty, on result trees written by hand: trials give pass@k and
pass^k, errors stay out of every rate and are listed with their causes, and two result sets
are called different only when the difference is larger than the noise.

The cast: *steady* passes 36 of 40 tasks; *close* passes 34 (within the noise of steady);
*shaky* passes 12 (far beyond it); *flaky* ran two tasks three times each."""

from __future__ import annotations

import io
import json
import re
from pathlib import Path

import pytest
from django.core.management import call_command

ENVIRONMENTS = ("micromail", "microchat")


def write_set(root: Path, name: str, outcomes: list[bool], *, trial_folder: str = "") -> None:
    for i, success in enumerate(outcomes):
        environment = ENVIRONMENTS[i % 2]
        folder = root / name / environment / f"task-{i:02d}" / trial_folder
        folder.mkdir(parents=True, exist_ok=True)
        result = {
            "success": success,
            "detail": "",
            "evaluation_time": 20.0,
            "condition_at": 10.0,
            "contact_get_time": 10.0 + (1 + i % 5 if name != "shaky" else 20 + i % 7),
            "contact_post_time": None,
            "category": "passive-absolute",
        }
        (folder / "results.json").write_text(json.dumps(result))


def grade(root: Path, *names: str) -> str:
    out = io.StringIO()
    call_command("bench", "grade", *names, "--results-dir", str(root), stdout=out)
    return out.getvalue()


@pytest.fixture
def results(tmp_path) -> Path:
    write_set(tmp_path, "steady", [i >= 4 for i in range(40)])
    write_set(tmp_path, "close", [i >= 6 for i in range(40)])
    write_set(tmp_path, "shaky", [i >= 28 for i in range(40)])
    # flaky: task-00 passes 2 of 3 trials, task-01 passes all 3.
    write_set(tmp_path, "flaky", [True, True])
    write_set(tmp_path, "flaky", [False, True], trial_folder="trial-2")
    write_set(tmp_path, "flaky", [True, True], trial_folder="trial-3")
    return tmp_path


def test_a_difference_beyond_the_noise_is_said_and_one_within_it_too(results):
    text = grade(results, "steady", "close", "shaky")
    table = text.split("Differences beyond the noise")[1]
    lines = {line.split("|")[0].strip(): line for line in table.splitlines() if "|" in line}
    assert lines["success: steady − close"].rstrip().endswith("within the noise")
    assert "+5.0 pts" in lines["success: steady − close"]
    assert lines["success: steady − shaky"].rstrip().endswith("beyond the noise")
    assert "+60.0 pts" in lines["success: steady − shaky"]
    # shaky reacts in 20–26 s, steady in 1–5 s: far apart on the median too.
    assert lines["median reaction: steady − shaky"].rstrip().endswith("beyond the noise")


def test_trials_give_pass_at_k_and_pass_hat_k(results):
    text = grade(results, "flaky")
    # pass@3: both tasks have a pass; pass^3: only task-01 passed every trial.
    assert "pass@3 100.0%, pass^3 50.0% over 2 tasks × 3 trials" in text
    assert "Task Success Rate: 83.3% (5/6)" in text
    assert "task-00 (trial 2)" in text


def test_errors_are_listed_with_their_cause_and_counted_in_no_rate(results):
    errored = results / "steady" / "microchat" / "task-41"
    errored.mkdir(parents=True)
    (errored / "error.txt").write_text(
        "the agent never opened its task page (it exited with code 2)\n\ndetails\n"
    )
    text = grade(results, "steady")
    assert "Task Success Rate: 90.0% (36/40)" in text
    assert re.search(r"success +\| 90\.0% \(36/40\) \[76\.9–96\.0%\]", text)
    assert "errors (not graded, not in any rate): 1" in text
    assert (
        "  microchat/task-41: the agent never opened its task page (it exited with code 2)" in text
    )
    by_environment = text.split("By environment:")[1].split("By category:")[0]
    assert re.search(r"microchat +\| 20 +\| 90\.0% \(18/20\)", by_environment)


def test_the_csv_counts_errors_apart(results):
    errored = results / "steady" / "micromail" / "task-40"
    errored.mkdir(parents=True)
    (errored / "error.txt").write_text("the agent reported its environment failed (exit code 75)\n")
    out = io.StringIO()
    call_command("bench", "grade", "steady", "--csv", "--results-dir", str(results), stdout=out)
    summary = dict(row.split(",", 1) for row in out.getvalue().split("\n\n")[1].splitlines())
    assert summary["Total Tasks"] == "40" and summary["Errors Not Graded"] == "1"
