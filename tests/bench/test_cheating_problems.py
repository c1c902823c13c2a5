"""What `bench validate` calls a problem in the cheating strategies' verdicts."""

from __future__ import annotations

from apps.bench.cheating import cheating_problems

IDS, NOOPS, ACTIVE = ["active", "passive", "noop"], {"noop"}, ["active"]


def verdicts(*passes: tuple[str, str]):
    return lambda agent, scenario: (agent, scenario) in passes


def test_passing_an_active_task_or_a_no_op_by_cheating_is_a_problem():
    passed = verdicts(("act_all", "active"), ("fixed_time", "noop"), ("quitter", "noop"))
    assert cheating_problems(passed, IDS, NOOPS, ACTIVE, "paper") == [
        "act_all passed active (acting on every item is rewarded)",
        "fixed_time passed no-op noop",
        "quitter passed noop (leaving at once is rewarded)",
    ]


def test_late_passive_passes_are_no_problem_and_the_original_rule_lets_quitters_pass_no_ops():
    passed = verdicts(("act_all", "passive"), ("fixed_time", "passive"), ("quitter", "noop"))
    assert cheating_problems(passed, IDS, NOOPS, ACTIVE, "original") == []
    assert cheating_problems(passed, IDS, NOOPS, ACTIVE, "paper") == [
        "quitter passed noop (leaving at once is rewarded)"
    ]
