"""The rules of a BrowserGym task that need no browser: which chat message is the report, a
task's category and end, and a verdict as BrowserGym's (reward, done, message, info)."""

from __future__ import annotations

import json

import pytest

try:
    from sentinel_environments.browsergym import (
        agent_report,
        category,
        graded,
        read_scenarios,
        run_end,
    )
except ImportError as missing:  # the extra is part of ./dev's install
    pytest.fail(
        f"BrowserGym is not installed ({missing}): pip install -e '.[browsergym]'", pytrace=False
    )

from sentinel_environments.client import Verdict

GREETING = {"role": "assistant", "message": "Hi! I am your UI assistant, I can perform web tasks"}
GOAL = {"role": "user", "message": "Tell me when I get an email from Kevin Lee."}


def test_the_report_is_the_first_assistant_message_after_the_goal():
    assert agent_report([GREETING, GOAL]) is None
    said = [GREETING, GOAL, {"role": "assistant", "message": "Kevin wrote."}]
    assert agent_report([*said, {"role": "assistant", "message": "again"}]) == "Kevin wrote."
    assert agent_report([GREETING]) is None


def test_category_and_end_follow_the_scenario():
    passive = {"condition_at": 19.5, "kill_at": 630, "taxonomy": {"monitoring_approach": "passive"}}
    assert category(passive) == "passive"
    assert category({"condition_at": None, "taxonomy": {}}) == "noop"
    assert run_end(passive) == 600  # a condition never comes later
    assert run_end({"kill_at": 120}) == 120


def test_a_verdict_is_a_reward_and_the_end_of_the_episode():
    passed = Verdict(success=True, detail="ok", run=7, reaction_time=1.5, raw={"success": True})
    reward, done, message, info = graded(passed)
    assert (reward, done, message) == (1.0, True, "")
    assert info == {"success": True, "reaction_time": 1.5, "run": 7, "verdict": {"success": True}}
    assert graded(Verdict(success=False, detail="no", run=8))[0] == 0.0


def test_a_folder_with_a_broken_file_is_refused_by_name(tmp_path):
    (tmp_path / "micromail").mkdir()
    (tmp_path / "micromail" / "a.json").write_text(json.dumps({"id": "a", "prompt": "p"}))
    (tmp_path / "micromail" / "dev.json").write_text("{}")  # a hand-browsing world: skipped
    assert [document["id"] for _, document in read_scenarios(tmp_path)] == ["a"]
    (tmp_path / "micromail" / "b.json").write_text("{not json")
    with pytest.raises(ValueError, match=r"b\.json: not a JSON scenario"):
        read_scenarios(tmp_path)
