"""The reference agent as a whole, a subprocess (its browser tools: test_tools.py).

The story of the end-to-end test: the self user asks to be told when Kevin Lee writes. A live
MicroMail run at speed 4 delivers a travel-policy mail first, then Kevin's. The agent (a real
Chromium, a scripted model over real HTTP) opens the task URL, calls wait_for, whose judge says
no to the first change and yes once Kevin's row appears; the script then contacts, through the
real contact form. The run's evaluation passes, and the agent's costs.json is exactly what the
model server says it served.
"""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import pytest

from tests import control_api
from tests.browser_agent.conftest import AGENT, REPO, served

pytestmark = pytest.mark.browser

KEVIN = "Kevin Lee"
ARRIVES_AT = 32.0  # simulated seconds: 8 wall seconds at speed 4, well after wait_for starts
SPEED_FACTOR = 4.0
MESSAGE = "Kevin Lee's email has arrived: 'Expense reports: submission window closes early'."


def kevin_scenario() -> dict:
    return {
        "id": "agent-loop-kevin",
        "environment": "micromail",
        "prompt": f"Tell me when I get an email from {KEVIN}.",
        "start_page": "HOST_ADDRESS/micromail",
        "condition_at": ARRIVES_AT,
        "event_timeline_end": 240.0,
        "kill_at": 240.0,
        "taxonomy": {"monitoring_approach": "passive", "milestone_type": "absolute"},
        "events": [
            {"time": 0.0, "type": "preload_emails", "payload": {"email_ids": ["base-01", "base-05"]}},
            {"time": 8.0, "type": "new_email", "payload": {"email_id": "base-36"}},
            {"time": ARRIVES_AT, "type": "new_email", "payload": {"email_id": "base-77"}},
        ],
        "eval_sql": f"SELECT EXISTS (SELECT 1 FROM emails WHERE sender_name = '{KEVIN}')",
    }  # fmt: skip


WAIT_THEN_CONTACT = {
    "model": "scripted-1",
    "agent": [
        {"call": "wait_for", "arguments": {"condition": f"an email from {KEVIN}", "timeout": 150}},
        {"when_last_result": "met: true", "call": "contact", "arguments": {"message": MESSAGE}},
        {"otherwise": True, "call": "terminate", "arguments": {"reason": "Kevin never wrote"}},
    ],
    "judge": {"yes_when_any": [KEVIN]},
}


def run_agent(
    task_dir: Path, server, *, task_url: str, contact_url: str, prompt: str = "Go.", **options
) -> subprocess.CompletedProcess:
    argv = [
        *AGENT,
        "--model=scripted-1",
        f"--base-url={server.base_url}",
        f"--task-url={task_url}",
        f"--contact-url={contact_url}",
        f"--prompt={prompt}",
        f"--task-dir={task_dir}",
        *(f"--{key.replace('_', '-')}={value}" for key, value in options.items()),
    ]
    env = dict(os.environ, PYTHONPATH=str(REPO), OPENAI_API_KEY="")
    return subprocess.run(argv, cwd=task_dir, env=env, capture_output=True, text=True, timeout=90)


def transcript(task_dir: Path) -> list[dict]:
    return [json.loads(line) for line in (task_dir / "transcript.jsonl").read_text().splitlines()]


def costs(task_dir: Path) -> dict:
    return json.loads((task_dir / "costs.json").read_text())


def matches_served(written: dict, stats: dict) -> bool:
    return (
        written["input_tokens"],
        written["output_tokens"],
        written["cached_tokens"],
        written["calls"],
        written["tool_calls"],
    ) == (
        stats["prompt_tokens"],
        stats["completion_tokens"],
        stats["cached_tokens"],
        stats["requests"] - stats["failed"],
        stats["tool_calls"],
    )


# --- the whole agent ---------------------------------------------------------------------------


def test_the_agent_waits_for_kevins_email_and_contacts(live_site, scripted_model, tmp_path):
    run = control_api.post(
        live_site,
        "/api/runs/",
        {"scenario_json": kevin_scenario(), "clock_mode": "live", "speed_factor": SPEED_FACTOR},
    )
    server = scripted_model(WAIT_THEN_CONTACT)
    done = run_agent(
        tmp_path,
        server,
        task_url=run["task_url"],
        contact_url=run["contact_url"],
        prompt=run["prompt"],
        kind="wait_for",
        speed_factor=SPEED_FACTOR,
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines()[-1] == "stopped: contacted the user"

    verdict = control_api.post(live_site, f"/api/runs/{run['id']}/evaluate/")
    assert verdict["success"] is True, verdict["detail"]
    assert verdict["contact_message"] == MESSAGE
    assert verdict["contact_get_time"] >= ARRIVES_AT / SPEED_FACTOR

    wait, contact = transcript(tmp_path)
    assert (wait["tool"], contact["tool"]) == ("wait_for", "contact")
    assert wait["result"].startswith(f"met: true — a new change mentions '{KEVIN}'")
    assert wait["url"].startswith(live_site) and "/micromail" in wait["url"]
    for step in (wait, contact):
        assert (tmp_path / step["screenshot"]).read_bytes()[:2] == b"\xff\xd8"  # a JPEG

    # On the run's clock: the judge was shown Kevin's row after it arrived and said yes; any
    # question before was about other changes, and said no. The contact step ends after the
    # log's contact, on the same clock: within seconds of it (its screenshot and transcript take
    # a few wall seconds on a loaded machine, four times as many simulated ones), not twice it.
    *before, last = wait["checks"]
    assert last["met"] is True and any(KEVIN in block for block in last["blocks"])
    assert all(not c["met"] and KEVIN not in "".join(c["blocks"]) for c in before)
    assert wait["sim_start"] < ARRIVES_AT <= last["sim_time"] <= wait["sim_time"]
    log = control_api.call(live_site, "GET", f"/api/runs/{run['id']}/events/")
    contacted = next(e["at"] for e in log if e["type"].startswith("contact"))
    assert last["sim_time"] <= contacted <= contact["sim_time"] < contacted + 10 * SPEED_FACTOR

    stats = served(server.base_url)
    assert stats["judge_requests"] >= 1 and stats["agent_requests"] == 2
    written = costs(tmp_path)
    assert matches_served(written, stats)
    # The steps' usage adds up to the costs, the judge's tokens included.
    assert sum(s["usage"]["input_tokens"] for s in (wait, contact)) == written["input_tokens"]


def test_the_token_budget_stops_the_agent_cleanly(static_site, scripted_model, tmp_path):
    server = scripted_model({"model": "scripted-1", "agent": [{"call": "sleep", "arguments": {"seconds": 0}}] * 20})  # fmt: skip
    done = run_agent(
        tmp_path,
        server,
        task_url=static_site.url + "/",
        contact_url=static_site.contact_url,
        kind="sleep",
        max_tokens_total=5000,
    )
    assert done.returncode == 0, done.stderr
    written = costs(tmp_path)
    spent = written["input_tokens"] + written["output_tokens"]
    assert spent >= 5000
    assert done.stdout.splitlines()[-1] == (
        f"stopped: token budget exhausted ({spent} of 5000 tokens spent)"
    )
    stats = served(server.base_url)
    assert stats["requests"] < 20 and matches_served(written, stats)
    last = transcript(tmp_path)[-1]
    assert (last["tool"], last["result"]) == (None, done.stdout.splitlines()[-1])


def test_the_wall_budget_cuts_a_long_sleep_short_and_stops(static_site, scripted_model, tmp_path):
    server = scripted_model({"model": "scripted-1", "agent": [{"call": "sleep", "arguments": {"seconds": 600}}]})  # fmt: skip
    done = run_agent(
        tmp_path,
        server,
        task_url=static_site.url + "/",
        contact_url=static_site.contact_url,
        kind="sleep",
        # Enough for Chromium's start and the first model turn on a fully loaded machine, so
        # the budget runs out during the sleep, not before it.
        max_wall=15,
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines()[-1] == "stopped: wall-clock budget exhausted (15 s)"
    sleep = transcript(tmp_path)[0]
    assert sleep["tool"] == "sleep" and sleep["result"].endswith(
        "of 600 s: the time budget is spent"
    )


def test_a_missing_api_key_for_the_official_api_is_one_line(tmp_path):
    env = {k: v for k, v in os.environ.items() if k not in ("OPENAI_API_KEY", "OPENAI_BASE_URL")}
    argv = [*AGENT, "--kind=sleep", "--model=gpt-4o", "--task-url=http://x/", "--contact-url=http://x/c", "--prompt=Go."]  # fmt: skip
    done = subprocess.run(argv, cwd=REPO, env=env, capture_output=True, text=True, timeout=60)
    assert done.returncode == 2
    assert done.stderr == (
        "browser_agent: error: OPENAI_API_KEY is not set (a local server given by --base-url "
        "needs none)\n"
    )
