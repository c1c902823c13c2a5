"""The reference agent: its browser tools on a real page, and the whole agent as a subprocess.

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

from apps.browser_agent.model import ChatModel, CostLedger, make_client
from apps.browser_agent.tools import TaskClock, Toolbox
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
        max_wall=6,
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines()[-1] == "stopped: wall-clock budget exhausted (6 s)"
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


# --- the tools on a real page ----------------------------------------------------------------


@pytest.fixture
def make_toolbox(agent_browser, static_site, scripted_model):
    """`make_toolbox(kind, wall_left)`: the tools on the shop page, the judge a scripted model."""
    server = scripted_model({"model": "scripted-1", "agent": [], "judge": {"yes_when_any": ["Pressed"]}})  # fmt: skip
    client = make_client(base_url=server.base_url, api_key="not-needed")
    agent_browser.visit_url(static_site.url + "/")

    def make(kind: str = "wait_for", wall_left=lambda: None) -> Toolbox:
        return Toolbox(
            agent_browser,
            ChatModel(client, "scripted-1", CostLedger("scripted-1")),
            kind=kind,
            contact_url=static_site.contact_url,
            clock=TaskClock(10.0),  # wait_for's 10 s between questions take 1 wall second
            wall_left=wall_left,
        )

    return make


@pytest.fixture
def toolbox(make_toolbox) -> Toolbox:
    return make_toolbox()


def test_the_description_numbers_the_elements_in_view(toolbox):
    seen = toolbox.browser.observe()
    assert seen.title == "Shop"
    for line in (
        '[1] link "Other page"',
        '[2] button "Press me"',
        '[3] input "Search"',
        '[4] select "Colour" selected="Red"',
    ):
        assert line in seen.description.splitlines()
    assert "# Shop" in seen.description
    assert seen.png[:4] == b"\x89PNG" and seen.jpeg[:2] == b"\xff\xd8"


def test_the_tools_act_on_numbered_elements(toolbox):
    toolbox.browser.observe()
    assert toolbox.dispatch("click", {"target": 2}).text == 'clicked [2] button "Press me"'
    toolbox.dispatch("type", {"target": "[3]", "text": "lamps"})
    toolbox.dispatch("type", {"target": 4, "text": "Blue"})
    after = toolbox.browser.observe().description
    assert "Pressed!" in after
    assert '[3] input "Search" value="lamps"' in after
    assert '[4] select "Colour" selected="Blue"' in after
    assert toolbox.dispatch("click", {"target": 1}).ends_task is None
    assert toolbox.browser.observe().title == "Other"
    assert toolbox.dispatch("go_back", {}).text.startswith("went back to")


@pytest.mark.parametrize(
    ("tool", "arguments", "result"),
    [
        ("click", {"target": 99}, "error: no element [99] on the page now; use a number from the latest description"),
        ("click", {"target": "the button"}, 'error: target must be an element number from the page description, got "the button"'),
        ("click", {"element": 2}, 'error: click takes target; got {"element": 2}'),
        ("type", {"target": 4, "text": "Green"}, "error: no option 'Green' in this select; its options are 'Red', 'Blue'"),
        ("scroll", {"direction": "left"}, "error: direction must be 'up' or 'down', got 'left'"),
        ("visit_url", {"url": "ftp://x"}, "error: cannot visit 'ftp://x': only http:// and https:// URLs"),
        ("sleep", {"seconds": 5}, "error: there is no tool 'sleep'; use one of the tools offered"),
        ("wait_for", {"condition": "x", "timeout": -1}, "error: timeout must be a finite number of seconds ≥ 0, got -1"),
        ("contact", {"message": " "}, "error: message must not be empty"),
    ],
)  # fmt: skip
def test_a_mistake_is_the_tools_result_not_a_crash(toolbox, tool, arguments, result):
    toolbox.browser.observe()
    assert toolbox.dispatch(tool, arguments).text == result


def test_contact_goes_through_the_form_and_only_the_contact_tool_may(toolbox, static_site):
    refused = toolbox.dispatch("visit_url", {"url": static_site.contact_url})
    assert refused.text == "error: that is the contact page: report with the contact tool instead"
    assert static_site.messages == []
    done = toolbox.dispatch("contact", {"message": "The button was pressed."})
    assert (done.text, done.ends_task) == ("contacted: Thank you.", "contacted the user")
    assert static_site.messages == ["The button was pressed."]


def test_wait_for_watches_the_page_with_the_model_as_judge(toolbox):
    toolbox.browser.page.evaluate(
        "setTimeout(() => { document.getElementById('out').textContent = 'Pressed!' }, 300)"
    )
    result = toolbox.dispatch("wait_for", {"condition": "the button is pressed", "timeout": 300})
    assert result.text.startswith("met: true — a new change mentions 'Pressed'")
    assert toolbox.judge.model.ledger.total.calls >= 1


def test_a_sleep_never_outlasts_the_wall_budget(make_toolbox):
    toolbox = make_toolbox("sleep", wall_left=lambda: 0.0)
    assert toolbox.dispatch("sleep", {"seconds": 600}).text == (
        "slept 0 of 600 s: the time budget is spent"
    )
