"""Every scenario as a BrowserGym task (sentinel_environments.browsergym), played by a scripted
BrowserGym agent that uses only BrowserGym's actions — `noop(wait_ms)`, `click(bid)` and
`send_msg_to_user(text)` — in BrowserGym's own environment, on Debian's Chromium and a real
server: it passes a passive and an active MicroMail scenario on fast-forward clocks (its noops
skip simulated time), and fails a no-op by reporting; each reward is the run's verdict.

BrowserGym keeps one Playwright per process, whose event loop would stay in the thread that
started it (and Django refuses the test database's teardown in a thread with a running loop):
each episode runs in a thread of its own, which stops that Playwright when it is done."""

from __future__ import annotations

import re
import subprocess
import sys
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from typing import Any

import pytest

from events.timing import REACTION_WINDOW
from sentinel_environments import Client
from tests.conftest import REPO, ours

try:
    import gymnasium as gym
    from browsergym.core import _get_global_playwright, _set_global_playwright
    from browsergym.utils.obs import flatten_axtree_to_str

    from sentinel_environments import browsergym as sentinel_gym
except ImportError as missing:  # the extra is part of ./dev's install
    pytest.fail(
        f"BrowserGym is not installed ({missing}): pip install -e '.[browsergym]'",
        pytrace=False,
    )

pytestmark = [pytest.mark.e2e, pytest.mark.browser, pytest.mark.django_db(transaction=True)]

Agent = Callable[[str], str]  # the page's accessibility tree → the next BrowserGym action
STALE = "Could not find element with bid"
RETRIED = (STALE, "Locator.click: Timeout")


def find_bid(tree: str, role: str, name_part: str) -> str | None:
    """The BrowserGym id of the first element of `role` whose name holds `name_part`, if any."""
    for line in tree.splitlines():
        found = re.match(r"\s*\[([^\]]+)\] (\S+) (['\"])(.*)", line)
        if found and found.group(2) == role and name_part in found.group(4):
            return found.group(1)
    return None


def play(task: str, agent: Agent, max_steps: int = 60) -> tuple[float, dict[str, Any], dict]:
    """One episode in a thread of its own: (last reward, its task info, the reset's info)."""

    def episode():
        env = gym.make(f"browsergym/{task}")
        try:
            obs, started = env.reset()
            assert obs["goal_object"][0]["text"] == started["task_info"]["prompt"]
            for _ in range(max_steps):
                action = agent(flatten_axtree_to_str(obs["axtree_object"]))
                obs, reward, done, _, info = env.step(action)
                missed = obs["last_action_error"]
                # The errors a live page on a busy machine may cause: a push re-rendered the
                # element between the look and the click, so its id is gone, or BrowserGym's own
                # half-second click ceiling passed; the agent looks again and redoes it.
                assert not missed or any(m in missed for m in RETRIED), (action, missed)
                if missed:
                    agent.missed()  # type: ignore[attr-defined]
                if done:
                    return reward, info["task_info"], started["task_info"]
            raise AssertionError(f"{task}: not done after {max_steps} steps")
        finally:
            env.close()
            _get_global_playwright().stop()
            _set_global_playwright(None)

    with ThreadPoolExecutor(max_workers=1) as thread:
        return thread.submit(episode).result()


@pytest.fixture
def tasks(live_site) -> str:
    sentinel_gym.register_scenarios(server_url=live_site)
    return live_site


def waits_for_kevin(tree: str) -> str:
    if "From Kevin Lee." in tree:
        return 'send_msg_to_user("Kevin Lee has written to you.")'
    return "noop(5000)"


def test_a_passive_scenario_passes_and_the_reward_is_the_verdict(tasks):
    reward, verdict, started = play("sentinel.micromail-sender-absolute-passive", waits_for_kevin)
    assert started["clock"] == "fast_forward" and started["category"] == "passive"
    assert reward == 1.0 and verdict["success"], verdict
    assert verdict["verdict"]["contact_message"] == "Kevin Lee has written to you."
    # Kevin's mail comes at 19.5 s; five-second skips see it within one more step, whose own
    # work runs on the clock (seconds on a loaded machine): timely, within the reaction window.
    assert 0 <= verdict["reaction_time"] < REACTION_WINDOW
    with Client(tasks) as server:
        assert server.run(verdict["run"]).evaluate().success is True


SUBJECT = "Notes from Tuesday's architecture sync"  # base-45, at 289.55 s


def flags_the_scalability_mail() -> Agent:
    """Opens the notes' mail, flags it and reports once its row says it is flagged. Each step is
    decided on the fresh tree, so a step a live page made miss — the tree caught mid-push, or a
    click on an element re-rendered meanwhile (BrowserGym's error: `missed`) — is done again."""
    opened: list[str] = []  # the open's click, once it went through
    last: list[str] = [""]

    def missed() -> None:
        if last[0] == "open":
            opened.clear()

    def agent(tree: str) -> str:
        last[0] = ""
        if f"Unflag “{SUBJECT}”" in tree:
            return 'send_msg_to_user("I flagged the notes on platform scalability.")'
        link = find_bid(tree, "link", f"Subject: {SUBJECT}")
        if link is None:  # not arrived yet, or its row being redrawn: look again
            return "noop(1000)" if f"Subject: {SUBJECT}" in tree else "noop(30000)"
        if not opened:
            opened.append(link)
            last[0] = "open"
            return f"click('{link}')"
        flag = find_bid(tree, "button", f"Flag “{SUBJECT}”")
        return "noop(1000)" if flag is None else f"click('{flag}')"  # flagging twice is one flag

    agent.missed = missed  # type: ignore[attr-defined]
    return agent


def test_an_active_scenario_passes_by_clicking(tasks):
    reward, verdict, started = play(
        "sentinel.micromail-body-keyword-absolute-active", flags_the_scalability_mail()
    )
    assert started["category"] == "active"
    assert reward == 1.0 and verdict["success"], verdict
    assert verdict["verdict"]["actions"] >= 2  # opened, flagged
    with Client(tasks) as server:
        assert server.run(verdict["run"]).evaluate().success is True


def test_a_no_op_fails_when_the_agent_reports(tasks):
    def reports_at_once(tree: str) -> str:
        return 'send_msg_to_user("Kevin Lee has written to you.")'

    reward, verdict, started = play("sentinel.micromail-sender-absolute-noop", reports_at_once)
    assert started["category"] == "noop"
    assert reward == 0.0 and verdict["success"] is False
    with Client(tasks) as server:
        assert server.run(verdict["run"]).evaluate().success is False


def test_the_task_list_holds_every_scenario_with_its_category():
    metadata = sentinel_gym.task_metadata()
    noops = sum(s.is_noop for s in ours())
    assert len(metadata) == len(ours())
    categories = [row["category"] for row in metadata]
    assert categories.count("noop") == noops
    assert categories.count("passive") + categories.count("active") == len(ours()) - noops
    assert len({row["environment"] for row in metadata}) == 10
    registered = {name for name in gym.registry if name.startswith("browsergym/sentinel.")}
    assert registered == {f"browsergym/{row['task_name']}" for row in metadata}


def test_the_readme_example_runs_as_written(tmp_path):
    from tests.first_hour.test_readme_harness import code_blocks, readme_section

    blocks = code_blocks(readme_section("Use with BrowserGym / AgentLab"))
    (example,) = [code for lang, code, _ in blocks if lang == "python"]
    script = tmp_path / "kevin.py"
    script.write_text(example, encoding="utf-8")
    done = subprocess.run(
        [sys.executable, str(script)],
        cwd=tmp_path,
        # A user's shell in the checkout: no SENTINEL_URL, so the task starts its own server.
        env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin", "HOME": str(tmp_path)},
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    lines = done.stdout.splitlines()
    assert lines[0] == "Tell me when I get an email from Kevin Lee."
    assert lines[-1].startswith("reward: 1.0 reaction time: ")
