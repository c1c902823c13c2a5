"""The dry run plays a timeline with no agent and checks condition_at against eval_sql."""

from __future__ import annotations

import io

import pytest
from django.core.management import call_command

from apps.scenarios.dry_run import dry_run, validate_timeline_entry
from apps.scenarios.models import Scenario
from tests.conftest import OUR_SCENARIOS, ours

pytestmark = pytest.mark.django_db


@pytest.fixture
def our_scenarios():
    call_command("loadscenarios", str(OUR_SCENARIOS), stdout=io.StringIO(), stderr=io.StringIO())
    return Scenario.objects.filter(environment="micromail", is_dev=False)


def test_every_micromail_scenario_of_ours_passes(our_scenarios):
    assert our_scenarios.count() == len(ours("micromail"))
    for scenario in our_scenarios:
        result = dry_run(scenario)
        assert result.warnings == [], scenario.path


def test_a_passive_condition_at_30_seconds_off_is_flagged(our_scenarios):
    scenario = our_scenarios.get(path="micromail/inbox-relative-passive.json")
    scenario.condition_at += 30
    result = dry_run(scenario)
    assert result.first_holds_at == 173.64
    assert result.warnings == [
        "passive task: the condition first holds at 173.64 s, but condition_at is 203.64 s (off by -30 s)",
        # Nothing arrives at the wrong time either: the inbox reads the same just before it.
        "the watched page HOST_ADDRESS/micromail does not change at condition_at 203.64 s: "
        "declare the page the prompt names (watch_page) or show the trigger there",
    ]


def test_each_step_shows_the_eval_value_and_baselines(our_scenarios):
    scenario = our_scenarios.get(path="micromail/inbox-relative-passive.json")
    steps = dry_run(scenario).steps
    assert [s.holds for s in steps].index(True) == 8
    assert steps[0].baselines["inbox_count"] == 12
    assert steps[-1].fires is True


def test_a_noop_whose_condition_holds_is_flagged(our_scenarios):
    scenario = our_scenarios.get(path="micromail/sender-absolute-noop.json")
    scenario.eval_sql = "SELECT COUNT(*) FROM emails"
    assert "no-op task, but the condition holds" in dry_run(scenario).warnings[0]


def test_timeline_entries_are_checked_against_schema_and_catalog():
    assert validate_timeline_entry("micromail", "new_email", {"email_id": "base-04"}) == []
    assert validate_timeline_entry("micromail", "preload_emails", {"email_ids": ["*"]}) == []
    assert (
        "not in catalog table 'emails': nope"
        in validate_timeline_entry("micromail", "new_email", {"email_id": "nope"})[0]
    )
    assert "unknown event type" in validate_timeline_entry("micromail", "explode", {})[0]
    assert "required" in validate_timeline_entry("micromail", "new_email", {})[0]


def test_an_active_task_is_solved_by_its_solution_at_condition_at(our_scenarios):
    with_solution = [s for s in our_scenarios if s.solution]
    assert with_solution
    for scenario in with_solution:
        assert dry_run(scenario).solution_holds is True, scenario.path


def test_a_solution_that_cannot_act_at_condition_at_is_flagged(our_scenarios):
    scenario = our_scenarios.get(path="micromail/attachment-name-absolute-active.json")
    scenario.condition_at = 5.0  # before the awaited mail arrives: opening it is rejected
    assert any("is rejected at condition_at 5 s" in w for w in dry_run(scenario).warnings)


def test_the_dry_run_notes_that_the_watched_page_changes(our_scenarios):
    scenario = our_scenarios.get(path="micromail/inbox-relative-passive.json")
    notes = dry_run(scenario).notes
    assert any(
        n.startswith("the watched page HOST_ADDRESS/micromail changes at condition_at 173.64 s")
        for n in notes
    ), notes
