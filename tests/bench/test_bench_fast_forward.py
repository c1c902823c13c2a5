"""`bench_fast_forward`'s pure parts: the subset it compares, the judge's phrases, the
comparison of two result trees (the command itself runs for minutes: README, Performance)."""

from __future__ import annotations

import json

from apps.bench.management.commands.bench_fast_forward import (
    comparison,
    condition_phrases,
    task_outcomes,
    two_per_environment,
)


def spec(id: str, environment: str, condition_at=None, approach="active", events=()) -> dict:
    return {
        "id": id,
        "environment": environment,
        "condition_at": condition_at,
        "taxonomy": {"monitoring_approach": approach},
        "events": list(events),
    }


def test_the_subset_is_a_passive_task_and_a_noop_per_environment():
    scenarios = [
        spec("mail-active", "micromail", 40.0),
        spec("mail-passive", "micromail", 50.0, approach="passive"),
        spec("mail-noop", "micromail"),
        spec("chat-active", "microchat", 30.0),
        spec("chat-noop", "microchat"),
        spec("chat-noop-2", "microchat"),
    ]
    assert two_per_environment(scenarios) == [
        "chat-active",
        "chat-noop",
        "mail-passive",
        "mail-noop",
    ]


def test_phrases_are_the_start_of_the_records_the_condition_entries_bring(tmp_path):
    (tmp_path / "micromail").mkdir()
    (tmp_path / "micromail" / "emails.jsonl").write_text(
        json.dumps({"id": "e1", "subject": "Expense reports: submission window closes"})
        + "\n"
        + json.dumps({"id": "e2", "subject": "Unrelated"})
        + "\n"
    )
    at_40 = {"time": 40.0, "type": "new_email", "payload": {"email_id": "e1"}}
    earlier = {"time": 10.0, "type": "new_email", "payload": {"email_id": "e2"}}
    scenarios = [
        spec("mail", "micromail", 40.0, events=[earlier, at_40]),
        spec("noop", "micromail"),
    ]
    assert condition_phrases(scenarios, tmp_path) == ["Expense reports: submiss"]


def test_the_comparison_counts_same_verdicts_reaction_gaps_and_model_calls():
    fast = {
        "a": {"success": True, "reaction": 10.0, "calls": 4},
        "b": {"success": False, "reaction": None, "calls": 3},
        "c": {"success": True, "reaction": 5.0, "calls": 2},
        "only-fast": {"success": True, "reaction": 1.0, "calls": 1},
    }
    live = {
        "a": {"success": True, "reaction": 10.6, "calls": 4},
        "b": {"success": True, "reaction": 30.0, "calls": 3},
        "c": {"success": True, "reaction": 7.5, "calls": 5},
    }
    result = comparison(fast, live, tolerance=1.0)
    assert result["tasks"] == 3 and result["same_verdict"] == 2 and result["differing"] == ["b"]
    assert result["max_reaction_gap_s"] == 2.5 and not result["within_tolerance"]
    assert result["same_calls"] == 2


def test_outcomes_are_read_from_a_results_tree_in_simulated_seconds(tmp_path):
    task = tmp_path / "micromail" / "t1"
    task.mkdir(parents=True)
    (task / "results.json").write_text(
        json.dumps(
            {
                "scenario_id": "t1",
                "success": True,
                "contact_get_time": 30.0,
                "condition_at": 20.0,
                "speed_factor": 2.0,
            }
        )
    )
    (task / "costs.json").write_text(json.dumps({"calls": 7}))
    assert task_outcomes(tmp_path) == {"t1": {"success": True, "reaction": 20.0, "calls": 7}}
