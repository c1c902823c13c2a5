"""`bench grade`'s category table shows the paper's future-work axes beside its categories:
tasks by persistence (an ephemeral condition holds only briefly) and by criteria (a judgement
against a rubric). Results written before the axes were recorded count as persistent and
objective, as every upstream task is."""

from __future__ import annotations

import io
import json
import re

from django.core.management import call_command


def test_the_category_table_breaks_the_tasks_down_by_persistence_and_criteria(tmp_path):
    tasks = [  # (axes recorded by bench run, success)
        ({"persistence": "ephemeral", "criteria": "objective"}, True),
        ({"persistence": "ephemeral", "criteria": "subjective"}, False),
        ({"persistence": "persistent", "criteria": "subjective"}, True),
        ({}, True),  # an older result: neither recorded
    ]
    for i, (axes, success) in enumerate(tasks):
        folder = tmp_path / "set" / "microchat" / f"task-{i}"
        folder.mkdir(parents=True)
        result = {
            "success": success,
            "detail": "",
            "evaluation_time": 20.0,
            "condition_at": 10.0,
            "contact_get_time": 12.0,
            "contact_post_time": None,
            "category": "active-absolute",
            **axes,
        }
        (folder / "results.json").write_text(json.dumps(result))
    out = io.StringIO()
    call_command("bench", "grade", "set", "--results-dir", str(tmp_path), stdout=out)
    table = out.getvalue().split("By category:")[1]
    for name, attempts, share in (
        ("active-absolute", 4, "75.0% (3/4)"),
        ("persistence: ephemeral", 2, "50.0% (1/2)"),
        ("persistence: persistent", 2, "100.0% (2/2)"),
        ("criteria: objective", 2, "100.0% (2/2)"),
        ("criteria: subjective", 2, "50.0% (1/2)"),
    ):
        assert re.search(rf"{re.escape(name)} +\| {attempts} +\| {re.escape(share)} \[", table)
