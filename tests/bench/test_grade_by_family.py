"""`bench grade` reports generated scenarios (`manage.py generate`) by their family."""

from __future__ import annotations

import io
import json
from pathlib import Path

from django.core.management import call_command

RESULTS = {
    # name: (category, success)
    "micromail-sender-absolute-passive-g7-0001": ("passive-absolute", True),
    "micromail-sender-absolute-passive-g7-0002": ("passive-absolute", False),
    "micromail-sender-absolute-passive-withheld-g7-0001": ("noop", True),
    "micromail-junk-relative-passive": ("passive-relative", True),  # hand-written: its own row
}


def grade(tmp_path: Path) -> list[str]:
    for name, (category, success) in RESULTS.items():
        folder = tmp_path / "results" / "gen" / "micromail" / name
        folder.mkdir(parents=True)
        condition = None if category == "noop" else 60.0
        result = {
            "success": success, "detail": "", "evaluation_time": 70.0,
            "condition_at": condition, "contact_get_time": condition and 65.0,
            "contact_post_time": None, "contact_message": None, "run": None,
            "category": category, "views": 3, "actions": 0,
        }  # fmt: skip
        (folder / "results.json").write_text(json.dumps(result))
    (tmp_path / "eval_config.yaml").write_text("agent_subprocess: [echo]\n")
    out = io.StringIO()
    call_command("bench", "grade", "gen", "--results-dir", str(tmp_path / "results"),
                 "--config", str(tmp_path / "eval_config.yaml"), stdout=out)  # fmt: skip
    return out.getvalue().splitlines()


def test_generated_results_get_a_table_by_family(tmp_path):
    lines = grade(tmp_path)
    start = lines.index("By family (generated scenarios):")
    table = lines[start + 3 : start + 6]
    rows = {line.split("|")[0].strip(): line.split("|")[1:3] for line in table}
    assert set(rows) == {
        "micromail/sender-absolute-passive",
        "micromail/sender-absolute-passive-withheld",
        "micromail/micromail-junk-relative-passive",
    }
    attempts, success = rows["micromail/sender-absolute-passive"]
    assert attempts.strip() == "2" and success.strip().startswith("50.0% (1/2)")
