"""`bench grade`'s category table shows the paper's future-work axes beside its categories:
tasks by persistence (an ephemeral condition holds only briefly) and by criteria (a judgement
against a rubric). Results written before the axes were recorded count as persistent and
objective, as every upstream task is. A comparison of result sets shows them too, in its text
and its HTML report, with each set's judged reports."""

from __future__ import annotations

import io
import json
import re
from pathlib import Path

from django.core.management import call_command

TASKS = [  # (axes recorded by bench run, success)
    ({"persistence": "ephemeral", "criteria": "objective"}, True),
    ({"persistence": "ephemeral", "criteria": "subjective"}, False),
    ({"persistence": "persistent", "criteria": "subjective"}, True),
    ({}, True),  # an older result: neither recorded
]
RUBRIC = {"must_mention": ["Pier 9"]}


def write_set(root: Path, name: str, tasks=TASKS, *, reaction: float = 2.0) -> None:
    """The tasks of one result set; the first carries a contact rubric its report meets."""
    for i, (axes, success) in enumerate(tasks):
        folder = root / name / "microchat" / f"task-{i}"
        folder.mkdir(parents=True)
        result = {
            "success": success,
            "detail": "",
            "evaluation_time": 20.0,
            "condition_at": 10.0,
            "contact_get_time": 10.0 + reaction,
            "contact_post_time": None,
            "category": "active-absolute",
            "contact_message": "The party is at Pier 9.",
            **({"contact_rubric": RUBRIC} if i == 0 else {}),
            **axes,
        }
        (folder / "results.json").write_text(json.dumps(result))


def grade(root: Path, *names: str, html: Path | None = None) -> str:
    out = io.StringIO()
    options = ["--html", str(html)] if html else []
    call_command("bench", "grade", *names, "--results-dir", str(root), *options, stdout=out)
    return out.getvalue()


def test_the_category_table_breaks_the_tasks_down_by_persistence_and_criteria(tmp_path):
    write_set(tmp_path, "set")
    table = grade(tmp_path, "set").split("By category:")[1]
    for name, attempts, share in (
        ("active-absolute", 4, "75.0% (3/4)"),
        ("persistence: ephemeral", 2, "50.0% (1/2)"),
        ("persistence: persistent", 2, "100.0% (2/2)"),
        ("criteria: objective", 2, "100.0% (2/2)"),
        ("criteria: subjective", 2, "50.0% (1/2)"),
    ):
        assert re.search(rf"{re.escape(name)} +\| {attempts} +\| {re.escape(share)} \[", table)


def test_a_comparison_shows_both_axes_and_each_sets_judged_reports(tmp_path):
    write_set(tmp_path, "fast")
    write_set(tmp_path, "slow", [(axes, True) for axes, _ in TASKS], reaction=100.0)
    text = grade(tmp_path, "fast", "slow", html=tmp_path / "report.html")
    success = text.split("Success by persistence and criteria\n")[1].split("\n\n")[0]
    assert re.search(r"persistent +\| ephemeral +\| objective +\| subjective", success)
    assert re.search(
        r"fast +\| 100.0% \(2/2\) +\| 50.0% \(1/2\) +\| 100.0% \(2/2\) +\| 50.0% \(1/2\)", success
    )
    timely = text.split("Timely success by persistence and criteria")[1].split("\n\n")[0]
    assert re.search(r"slow +\| 0.0% \(0/2\) +\| 0.0% \(0/2\)", timely)  # passed, all late
    assert "fast: Success with a correct report (tasks with a contact rubric): 100.0% (1/1)" in text
    html = (tmp_path / "report.html").read_text()
    axes = html.split("<h2>Success by persistence and criteria</h2>")[1].split("<h2>")[0]
    assert "<th>ephemeral</th>" in axes and "<td>50.0% (1/2)</td>" in axes
    assert "<h2>Timely success by persistence and criteria</h2>" in html
    assert "<h2>Reports of slow (judged by keywords)</h2>" in html
    assert "<td>active-absolute, ephemeral, subjective</td>" in html  # each task's own axes
