"""Short MicroMail scenarios for the harness tests, derived from the real ones.

The real timelines last 180 s at speed 4; these keep the same events and eval_sql but put the
condition at 40 s (10 wall s at speed 4) and kill_at at 60, so a whole benchmark takes ~20 s.
Each prompt carries a `[[script: …]]` for tests/bench/scripted_agent.py.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

from tests.conftest import OUR_SCENARIOS

REPO = Path(__file__).resolve().parents[2]
REAL = OUR_SCENARIOS / "micromail"
AGENT = Path(__file__).with_name("scripted_agent.py")


def shorten(
    source: str,
    new_id: str,
    script: str,
    *,
    condition_at: float = 40.0,
    kill_at: float = 60.0,
    end: float = 100.0,
    environment: str = "micromail",
) -> dict:
    data = json.loads((OUR_SCENARIOS / environment / f"{source}.json").read_text())
    old = data["condition_at"]
    factor = condition_at / (old if old is not None else 300.0)
    events = []
    for event in data["events"]:
        if old is not None and event["time"] > old:
            continue  # nothing after the condition: the test run ends soon after it
        time = round(event["time"] * factor, 3)
        if time <= end:
            events.append({**event, "time": time})
    data.update(
        id=new_id,
        kill_at=kill_at,
        event_timeline_end=end,
        events=events,
        condition_at=None if old is None else condition_at,
        prompt=f"{data['prompt']}\n[[script: {script}]]",
    )
    return data


TEST_SCENARIOS = [
    # id, source, script, options. Costs are written before the contact: after it the harness
    # ends the agent once the grace period is over, which a loaded machine can reach while the
    # contact's answer is still on its way.
    (
        "bench-passive",
        "sender-absolute-passive",
        "poll select-base-77; costs 10000 500 4 upstream; contact",
        {},
    ),
    (
        "bench-active",
        "body-keyword-absolute-active",
        "poll select-base-45; action open_email base-45; action flag base-45; "
        "costs 20000 1000 6; contact",
        {},
    ),
    # Leaves a child behind when it exits by itself: the harness kills it anyway. It exits
    # after the run's end (kill_at 60 = 15 wall s at speed 4): a no-op passes only if the agent
    # is still there then (the paper's rule).
    ("bench-noop", "sender-absolute-noop", "spawn; costs 5000 100 2; sleep 16.5", {}),
    ("bench-early", "inbox-relative-passive", "costs 1000 50 1; contact", {}),
    ("bench-hung", "junk-relative-passive", "spawn; hang", {"condition_at": 16.0, "kill_at": 20.0}),
    # Contacts in time, then lingers: killed after the grace period, still a success.
    (
        "bench-linger",
        "unread-absolute-passive",
        "poll select-cc-02; contact; hang",
        {"condition_at": 16.0, "kill_at": 20.0},
    ),
]


@pytest.fixture
def bench_scenarios(tmp_path, settings):
    """A scenario folder with the short scenarios, used by the embedded server."""
    root = tmp_path / "scenarios"
    (root / "micromail").mkdir(parents=True)
    for scenario_id, source, script, options in TEST_SCENARIOS:
        data = shorten(source, scenario_id, script, **options)
        (root / "micromail" / f"{scenario_id}.json").write_text(json.dumps(data, indent=1))
    settings.SENTINEL_SCENARIO_DIR = root
    return root


@pytest.fixture
def bench_config(tmp_path):
    """An eval_config.yaml running the scripted agent, with short deadlines and a price."""

    def write(**extra) -> Path:
        config = {
            "speed_factor": 4,
            "parallel": 10,
            "reaction_window": 4,
            "grace": 5,
            "agent_subprocess": [
                sys.executable,
                str(AGENT),
                "__TASK_URL__",
                "__CONTACT_URL__",
                "__TASK_PROMPT__",
            ],
            "prices": {"test-model": {"input": 2.0, "output": 10.0}},
            **extra,
        }
        path = tmp_path / "eval_config.yaml"
        import yaml

        path.write_text(yaml.safe_dump(config))
        return path

    return write
