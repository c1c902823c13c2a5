"""`bench export-trajectories` on a results tree written by hand: a reference agent's
transcript becomes the record's steps, and bad input is one line naming it."""

from __future__ import annotations

import io
import json

import pytest
from django.core.management import call_command
from django.core.management.base import CommandError

from tests.bench.test_report import results_tree  # noqa: F401

STEPS = [
    {"step": 1, "sim_start": 1.0, "sim_time": 70.0, "url": "http://h/r/t/micromail/",
     "observation": "URL: http://h/r/t/micromail/\nTitle: Inbox", "tool": "wait_for",
     "arguments": {"condition": "mail", "timeout": 90}, "result": "met: true",
     "screenshot": "transcript/step-001.jpg", "usage": {"input_tokens": 10, "output_tokens": 2},
     "checks": [{"sim_time": 61.0, "blocks": ["+ the mail"], "met": True, "why": "it came"}]},
    {"step": 2, "sim_start": 71.0, "sim_time": 75.0, "tool": "contact",
     "arguments": {"message": "done"}, "result": "contacted", "screenshot": None},
]  # fmt: skip


def export(root, *args) -> list[dict]:
    out = io.StringIO()
    call_command("bench", "export-trajectories", "graded", "--results-dir", str(root), *args,
                 stdout=out, stderr=io.StringIO())  # fmt: skip
    return [json.loads(line) for line in out.getvalue().splitlines()]


def test_a_transcript_becomes_the_steps_with_screenshots_under_the_result_set(results_tree):  # noqa: F811
    folder = results_tree / "results" / "graded" / "micromail" / "mail-passive"
    (folder / "transcript.jsonl").write_text("\n".join(json.dumps(s) for s in STEPS))
    records = {r["task"]: r for r in export(results_tree / "results")}
    assert set(records) == {"mail-passive", "mail-active", "mail-noop", "mail-late"}
    passive = records["mail-passive"]
    assert passive["steps_from"] == "transcript"
    first, second = passive["steps"]
    assert (first["sim_start"], first["sim_time"], second["sim_time"]) == (1.0, 70.0, 75.0)
    assert first["observation"] == {
        "url": "http://h/r/t/micromail/",
        "text": "URL: http://h/r/t/micromail/\nTitle: Inbox",
        "screenshot": "micromail/mail-passive/transcript/step-001.jpg",
    }
    assert first["action"]["tool"] == "wait_for" and first["checks"][0]["blocks"] == ["+ the mail"]
    assert passive["reward"]["success"] is True and passive["reward"]["reaction_time"] == 15.0
    assert records["mail-noop"]["steps_from"] == "log" and records["mail-noop"]["steps"] == []


def test_a_missing_result_set_is_one_line(tmp_path):
    with pytest.raises(CommandError, match=r"RESULTS: no result set at nope \(nor under "):
        call_command("bench", "export-trajectories", "nope", "--results-dir", str(tmp_path))
