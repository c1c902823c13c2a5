"""`bench run --clock fast-forward`: the reference agents skip instead of waiting, on real
subprocesses driving Debian's Chromium through the embedded server, their model the scripted
server. The cast is test_reference_agents_e2e's: a passive MicroMail task (Kevin Lee writes at
40 s) and its no-op (he never does), kill_at 160 s, at speed 1.

- the wait_for agent passes both on fast_forward clocks, its runs' logs hold the skips, and
  results.json says which clock each task ran on;
- the sleep agent asks the model exactly as often on a fast-forward clock as on a live one
  (the same script turns), each of its sleeps one skip.
"""

from __future__ import annotations

import io
import json
from pathlib import Path

import pytest
import yaml
from django.core.management import call_command

from apps.browser_agent.scripted_model import parse_script, scripted_model_server
from tests.bench.test_reference_agents_e2e import MODEL, paper_scenarios  # noqa: F401

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.browser]

WAIT_FOR = {
    "model": MODEL,
    "agent": [
        {
            "call": "wait_for",
            "arguments": {"condition": "the awaited email arrives", "timeout": 600},
        },
        {
            "when_last_result": "met: true",
            "call": "contact",
            "arguments": {"message": "The email you were waiting for has arrived."},
        },
        {"otherwise": True, "call": "terminate", "arguments": {"reason": "it never arrived"}},
    ],
    # Kevin Lee's email (the passive's condition) by its subject: on the no-op, where the agent
    # starts watching before Maya's urgent mail arrives, his older email's row changes too.
    "judge": {"yes_when_any": ["submission window closes early"]},
}
SLEEP = {
    "model": MODEL,
    "agent": [
        {"call": "sleep", "arguments": {"seconds": 8}},
        {"call": "sleep", "arguments": {"seconds": 8}},
        {"call": "read_page"},
        {"call": "terminate", "arguments": {"reason": "done looking"}},
    ],
}


def bench(*args: str) -> str:
    out = io.StringIO()
    call_command("bench", *args, stdout=out)
    return out.getvalue()


def configure(path: Path, base_url: str, kind: str) -> Path:
    path.write_text(
        yaml.safe_dump(
            {
                "speed_factor": 1,
                "parallel": 2,
                "grace": 5,
                "agent": {"kind": kind, "model": MODEL, "base_url": base_url},
            }
        )
    )
    return path


def results(root: Path, name: str) -> dict[str, dict]:
    return {
        folder.name: json.loads((folder / "results.json").read_text())
        for folder in (root / name / "micromail").iterdir()
    }


def logged(root: Path, name: str, task: str) -> list[dict]:
    lines = (root / name / "micromail" / task / "events.jsonl").read_text().splitlines()
    return [json.loads(line) for line in lines[1:]]  # after the header (export_run's format)


def transcript(root: Path, name: str, task: str) -> list[dict]:
    text = (root / name / "micromail" / task / "agent" / "transcript.jsonl").read_text()
    return [json.loads(line) for line in text.splitlines()]


def test_the_wait_for_agent_skips_to_the_email_and_passes_both_tasks(paper_scenarios, tmp_path):  # noqa: F811
    root = tmp_path / "results"
    with scripted_model_server(parse_script(WAIT_FOR)) as model:
        config = configure(tmp_path / "eval_config.yaml", model.base_url, "wait_for")
        log = bench(
            "run",
            "ff",
            "--config",
            str(config),
            "--results-dir",
            str(root),
            "--clock",
            "fast-forward",
            "--awake",
            "1",  # paced: one agent works while the other's waits are held (pacing.py)
        )
    print(log)
    assert "(clock: fast_forward)" in log and "ran=2 passed=2 failed=0 errors=0" in log
    assert json.loads((root / "ff" / "manifest.json").read_text())["config"]["awake"] == 1
    outcome = results(root, "ff")
    assert {r["clock"] for r in outcome.values()} == {"fast_forward"}
    passive = outcome["ref-passive"]
    # Reacted within the judge's longest rate limit (60 s): the same rules as on a live clock.
    assert passive["success"] and 0 <= passive["reaction_time"] < 60.0
    events = logged(root, "ff", "ref-passive")
    skips = [e["payload"] for e in events if e["type"] == "skip"]
    contact = next(e for e in events if e["type"] == "contact_get")
    assert skips and all(s["from"] < s["to"] <= contact["at"] for s in skips)
    assert {s["why"] for s in skips} <= {"slept", "change", "timeout"}
    # The transcript is on the run's clock across the skips: the judge saw Kevin's email after
    # it fired (40 s), and the contact step ended just after the log's contact.
    wait, reported = transcript(root, "ff", "ref-passive")
    arrived = next(e["at"] for e in events if e["type"] == "new_email" and e["at"] == 40.0)
    met = [c for c in wait["checks"] if c["met"]]
    assert met and arrived <= met[0]["sim_time"] <= contact["at"]
    assert contact["at"] <= reported["sim_time"] < contact["at"] + 5.0
    noop = [e["payload"] for e in logged(root, "ff", "ref-noop") if e["type"] == "skip"]
    assert (noop[-1]["to"], noop[-1]["why"]) == (160.0, "kill_at")  # it watched to the end
    grade = bench("grade", "ff", "--results-dir", str(root))
    assert "Clock: fast_forward" in grade


def test_the_sleep_agent_asks_the_model_as_often_on_both_clocks(paper_scenarios, tmp_path):  # noqa: F811
    root = tmp_path / "results"
    served = {}
    for clock in ("live", "fast-forward"):
        with scripted_model_server(parse_script(SLEEP)) as model:
            config = configure(tmp_path / f"{clock}.yaml", model.base_url, "sleep")
            log = bench(
                "run", clock, "--config", str(config), "--results-dir", str(root), "--clock", clock
            )
            print(log)
            assert "errors=0" in log
            served[clock] = model.model.stats()
    assert served["live"]["requests"] == served["fast-forward"]["requests"] > 0
    for task in ("ref-passive", "ref-noop"):
        skips = [e for e in logged(root, "fast-forward", task) if e["type"] == "skip"]
        assert [s["payload"]["to"] - s["payload"]["from"] for s in skips] == pytest.approx([8, 8])
        assert not [e for e in logged(root, "live", task) if e["type"] == "skip"]
        costs = {
            clock: json.loads(
                (root / clock / "micromail" / task / "agent" / "costs.json").read_text()
            )
            for clock in ("live", "fast-forward")
        }
        assert costs["live"]["calls"] == costs["fast-forward"]["calls"]
        assert costs["live"]["tool_calls"] == costs["fast-forward"]["tool_calls"]
