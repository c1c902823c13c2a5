"""A passed no-op needs its agent there at the end of the run (the paper: "the simulation ends
while the agent is still working or monitoring"); the original harness's looser rule passes an
agent that quit at once."""

from __future__ import annotations

from apps.bench.outcomes import noop_rule_applied

PASSED_NOOP = {"success": True, "detail": "eval_sql returned 0", "category": "noop"}
END = 150.0  # wall seconds


def test_a_quitter_fails_a_no_op_under_the_papers_rule():
    quitter = {**PASSED_NOOP, "agent_killed": False, "agent_left_at": 0.4}
    graded = noop_rule_applied(quitter, "paper", END)
    assert graded["success"] is False and graded["server_success"] is True
    assert graded["detail"].endswith("the agent left at 0.40 s, before the run's end at 150.00 s")


def test_an_agent_there_at_the_end_passes_it():
    stopped = {**PASSED_NOOP, "agent_killed": True, "agent_left_at": None}
    stayed = {**PASSED_NOOP, "agent_killed": False, "agent_left_at": 150.2}
    assert noop_rule_applied(stopped, "paper", END)["success"] is True
    assert noop_rule_applied(stayed, "paper", END)["success"] is True


def test_the_original_rule_passes_the_quitter_and_targeted_tasks_are_untouched():
    quitter = {**PASSED_NOOP, "agent_killed": False, "agent_left_at": 0.4}
    assert noop_rule_applied(quitter, "original", END)["success"] is True
    passive = {**quitter, "category": "passive-absolute"}
    assert noop_rule_applied(passive, "paper", END) == passive
