"""Every trigger of ours can be seen: the page the prompt tells the agent to watch (its
`watch_page`, else its start page) reads differently at `condition_at` than just before.

On a virtual clock, in process, no browser: apps.scenarios.watching renders the page with the
environment's own view on the timeline folded in memory. One test also renders it the way an
agent gets it (a stored run, the test client) to show that the check sees what the agent sees.
"""

from __future__ import annotations

import dataclasses
import io
import json
from pathlib import Path

import pytest
from django.conf import settings
from django.core.management import call_command
from django.test import Client

from apps.kit.links import start_page_path
from apps.kit.visible import visible_text
from apps.scenarios.format import ScenarioError, load_scenario_file, parse_scenario
from apps.scenarios.watching import JUST_BEFORE, check_watched
from events import lifecycle
from events.models import ClockMode
from tests.conftest import OUR_SCENARIOS

TARGETED = sorted(
    path
    for path in OUR_SCENARIOS.glob("*/*.json")
    if path.name != "dev.json" and load_scenario_file(path).condition_at is not None
)


@pytest.mark.parametrize("path", TARGETED, ids=lambda p: f"{p.parent.name}/{p.stem}")
def test_the_watched_page_changes_at_condition_at(path: Path):
    check = check_watched(load_scenario_file(path))
    assert check is not None and check.changes, check


def test_every_environment_has_targeted_scenarios_checked():
    assert len({path.parent.name for path in TARGETED}) == 10
    assert len(TARGETED) >= 80


def test_a_page_the_trigger_does_not_reach_is_reported():
    # MicroDin's feed shows nothing of a job posted: the prompt's Jobs page does.
    jobs = load_scenario_file(OUR_SCENARIOS / "microdin" / "jobs-absolute-passive.json")
    check = check_watched(dataclasses.replace(jobs, watch_page=""))
    assert check is not None and not check.changes
    assert "HOST_ADDRESS/microdin does not change at condition_at 196.4 s" in check.detail


def test_no_op_scenarios_have_nothing_to_watch():
    noop = load_scenario_file(OUR_SCENARIOS / "microdin" / "jobs-noop.json")
    assert check_watched(noop) is None


def test_watch_page_must_be_a_page_of_the_environment():
    data = json.loads((OUR_SCENARIOS / "microdin" / "jobs-absolute-passive.json").read_text())
    data["watch_page"] = "HOST_ADDRESS/microtube/watch"
    with pytest.raises(ScenarioError, match="watch_page: must be a page of microdin"):
        parse_scenario(data, source="x.json")


@pytest.mark.django_db
def test_the_check_sees_what_the_agent_sees():
    """The in-memory render reads like the run's own page fetched by a client, before and after."""
    scenario = load_scenario_file(OUR_SCENARIOS / "microdin" / "jobs-absolute-passive.json")
    run = lifecycle.create_run(
        scenario.to_run_spec(),
        clock_mode=ClockMode.VIRTUAL,
        catalog_dir=Path(settings.SENTINEL_CATALOG_DIR),
    )
    url = start_page_path(run).replace(f"/{run.environment}", "/microdin/jobs/", 1)
    client = Client()
    texts = []
    for at in (scenario.condition_at - JUST_BEFORE, scenario.condition_at):
        lifecycle.advance(run, at)
        texts.append(visible_text(client.get(url).content.decode()))
    assert texts[0] != texts[1]
    assert "7 results" in texts[0] and "8 results" in texts[1]


def test_checkscenarios_names_a_scenario_whose_trigger_does_not_show(tmp_path):
    data = json.loads((OUR_SCENARIOS / "microdin" / "jobs-absolute-passive.json").read_text())
    del data["watch_page"]
    (tmp_path / "microdin").mkdir()
    (tmp_path / "microdin" / "jobs.json").write_text(json.dumps(data, indent=2))
    out = io.StringIO()
    call_command("checkscenarios", str(tmp_path), stdout=out)
    lines = out.getvalue().splitlines()
    assert any(
        line.startswith("unseen: ") and "jobs.json: the watched page HOST_ADDRESS/microdin " in line
        for line in lines
    ), lines
    assert "watched pages: 0 of 1 targeted scenarios change visibly at condition_at" in lines
