"""Conformance: every MicroMail scenario is solvable over HTTP and not trivially passed.

(a) The original SentinelBench scenarios and catalog (../shared/upstream, skipped when absent).
(b) Our own scenarios in scenarios/micromail/ with their `solution` steps, over fixtures/.

For a normal scenario: evaluating right after create fails; advancing to kill_at, doing the
requisite actions over HTTP and visiting /contact succeeds (and, for active scenarios, the
same without the actions fails). For a no-op: never contacting succeeds, contacting fails.
"""

from __future__ import annotations

import json
import shutil
from dataclasses import replace
from pathlib import Path

import pytest
from django.conf import settings
from django.test import Client

from apps.scenarios.format import DEV_FILENAME, Scenario, load_scenario_file
from events import lifecycle
from events.evaluation import evaluate, grading_snapshot
from events.models import ClockMode
from events.projection import state_at
from events.registry import get_environment
from events.sandbox import is_truthy, run_eval_sql

pytestmark = pytest.mark.django_db

REPO = Path(__file__).resolve().parents[2]
UPSTREAM = REPO.parent / "shared" / "upstream"
UPSTREAM_CATALOG = UPSTREAM / "catalogs"


def _kind(path: Path) -> str:
    """ "noop", "active" (needs a solution) or "normal", read from the raw file.

    Raw JSON on purpose: a scenario that does not validate must fail its own tests, not break
    the collection of this module.
    """
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return "normal"
    if data.get("condition_at") is None:
        return "noop"
    active = (data.get("taxonomy") or {}).get("monitoring_approach") == "active"
    return "active" if active and data.get("solution") else "normal"


def scenario_files(folder: Path, *kinds: str) -> list:
    """One pytest param per scenario file of the given kinds (a skip when there are none)."""
    files = (
        sorted(p for p in folder.glob("*.json") if p.name != DEV_FILENAME)
        if folder.is_dir()
        else []
    )
    chosen = [pytest.param(p, id=p.stem) for p in files if _kind(p) in kinds]
    if not chosen:
        reason = f"no {'/'.join(kinds)} scenarios in {folder}"
        return [pytest.param(None, marks=pytest.mark.skip(reason=reason), id="none")]
    return chosen


UPSTREAM_DIR = UPSTREAM / "scenarios" / "micromail"
OUR_DIR = REPO / "scenarios" / "micromail"
# Upstream files carry no `solution`: their requisite actions are listed below instead.
UPSTREAM_TASKS = scenario_files(UPSTREAM_DIR, "normal", "active")
UPSTREAM_NOOPS = scenario_files(UPSTREAM_DIR, "noop")
OUR_TASKS = scenario_files(OUR_DIR, "normal", "active")
OUR_ACTIVE = scenario_files(OUR_DIR, "active")
OUR_NOOPS = scenario_files(OUR_DIR, "noop")

# What a user must do in the original scenarios beyond noticing: their eval_sql requires the
# message to have been read, i.e. opened in the client. (Upstream's own test lists none for
# micromail, so these two could never pass there without a browser.)
UPSTREAM_OPENS: dict[str, list[str]] = {
    "micromail-attachment-name-absolute-active": ["att-14"],
    "micromail-cc-relative-active": ["cc-03", "cc-04", "cc-05"],
}


def start(scenario: Scenario, catalog_dir: Path | None):
    return lifecycle.create_run(
        scenario.to_run_spec(), clock_mode=ClockMode.VIRTUAL, catalog_dir=catalog_dir
    )


def contact(run) -> None:
    assert Client().get(f"/r/{run.token}/contact").status_code == 200


def sql_holds(run) -> bool:
    """The scenario's eval_sql on the current state, without the contact gate."""
    outcome = run_eval_sql(run.scenario["eval_sql"], grading_snapshot(run).write)
    assert outcome.ok, outcome.error
    return is_truthy(outcome.value)


def open_in_the_client(run, email_ids: list[str]) -> None:
    browser = Client()
    for email_id in email_ids:
        assert browser.get(f"/r/{run.token}/micromail/?email={email_id}").status_code == 200


def perform_solution(run, scenario: Scenario) -> None:
    for step in scenario.solution:
        response = Client().post(
            f"/r/{run.token}/actions", json.dumps(step), content_type="application/json"
        )
        assert response.status_code == 201, response.content


# --- (a) upstream -----------------------------------------------------------------------------


@pytest.fixture(scope="session")
def upstream_micromail_catalog(tmp_path_factory) -> Path:
    """The upstream catalog's shared files and micromail folder, in a temporary directory.

    Workaround: the core loader rejects the whole upstream catalog because one other
    environment's table (microgram/suggestions.jsonl) has records without an `id`.
    """
    if not UPSTREAM_CATALOG.is_dir():
        pytest.skip("../shared/upstream is absent")
    directory = tmp_path_factory.mktemp("upstream-catalog")
    for name in ("users.json", "entities.json"):
        shutil.copyfile(UPSTREAM_CATALOG / name, directory / name)
    shutil.copytree(UPSTREAM_CATALOG / "micromail", directory / "micromail")
    return directory


@pytest.fixture
def upstream_catalog(settings, upstream_micromail_catalog):
    settings.SENTINEL_CATALOG_DIR = upstream_micromail_catalog
    return upstream_micromail_catalog


def upstream(path: Path) -> Scenario:
    return load_scenario_file(path)


@pytest.mark.upstream
@pytest.mark.parametrize("path", UPSTREAM_TASKS)
def test_upstream_scenario_fails_when_evaluated_right_after_create(path, upstream_catalog):
    assert evaluate(start(upstream(path), upstream_catalog)).success is False


@pytest.mark.upstream
@pytest.mark.parametrize("path", UPSTREAM_TASKS)
def test_upstream_eval_sql_is_false_until_condition_at_and_true_from_it(path, upstream_catalog):
    scenario = upstream(path)
    run = start(scenario, upstream_catalog)
    opens = UPSTREAM_OPENS.get(scenario.id, [])
    lifecycle.advance(run, scenario.condition_at - 0.01)
    open_in_the_client(run, [i for i in opens if state_at(run).has(i)])
    assert sql_holds(run) is False
    lifecycle.advance(run, scenario.condition_at)
    open_in_the_client(run, opens)
    assert sql_holds(run) is True


@pytest.mark.upstream
@pytest.mark.parametrize("path", UPSTREAM_TASKS)
def test_upstream_scenario_passes_when_the_agent_acts_and_contacts(path, upstream_catalog):
    scenario = upstream(path)
    run = start(scenario, upstream_catalog)
    lifecycle.advance(run, scenario.kill_at)
    open_in_the_client(run, UPSTREAM_OPENS.get(scenario.id, []))
    contact(run)
    verdict = evaluate(run)
    assert verdict.success is True, verdict.detail


@pytest.mark.upstream
@pytest.mark.parametrize("scenario_id", sorted(UPSTREAM_OPENS))
def test_upstream_active_scenario_fails_without_reading_the_mail(scenario_id, upstream_catalog):
    path = UPSTREAM_DIR / f"{scenario_id.removeprefix('micromail-')}.json"
    if not path.is_file():
        pytest.skip(f"{path} is absent")
    scenario = upstream(path)
    run = start(scenario, upstream_catalog)
    lifecycle.advance(run, scenario.kill_at)
    contact(run)
    assert evaluate(run).success is False


@pytest.mark.upstream
@pytest.mark.parametrize("path", UPSTREAM_NOOPS)
def test_upstream_noop_passes_when_the_agent_never_contacts(path, upstream_catalog):
    scenario = upstream(path)
    run = start(scenario, upstream_catalog)
    lifecycle.advance(run, scenario.kill_at)
    assert evaluate(run).success is True


@pytest.mark.upstream
@pytest.mark.parametrize("path", UPSTREAM_NOOPS)
def test_upstream_noop_fails_when_the_agent_contacts(path, upstream_catalog):
    scenario = upstream(path)
    run = start(scenario, upstream_catalog)
    lifecycle.advance(run, scenario.kill_at)
    contact(run)
    assert evaluate(run).success is False


# --- (b) our scenarios ------------------------------------------------------------------------


def ours(path: Path) -> Scenario:
    return load_scenario_file(path)


def our_catalog() -> Path:
    return Path(settings.SENTINEL_CATALOG_DIR)


def solution_steps_possible_now(run, scenario: Scenario) -> Scenario:
    """The solution restricted to steps about mail that has already arrived."""
    mail = state_at(run)
    steps = tuple(
        step
        for step in scenario.solution
        if "email_id" not in step["payload"] or mail.has(step["payload"]["email_id"])
    )
    return replace(scenario, solution=steps)


@pytest.mark.parametrize("path", OUR_TASKS)
def test_our_scenario_fails_when_evaluated_right_after_create(path):
    assert evaluate(start(ours(path), our_catalog())).success is False


@pytest.mark.parametrize("path", OUR_TASKS)
def test_our_eval_sql_is_false_until_condition_at_and_true_from_it(path):
    scenario = ours(path)
    run = start(scenario, our_catalog())
    lifecycle.advance(run, scenario.condition_at - 0.01)
    perform_solution(run, solution_steps_possible_now(run, scenario))
    assert sql_holds(run) is False
    lifecycle.advance(run, scenario.condition_at)
    perform_solution(run, scenario)
    assert sql_holds(run) is True


@pytest.mark.parametrize("path", OUR_TASKS)
def test_our_scenario_passes_with_its_solution_and_contact(path):
    scenario = ours(path)
    run = start(scenario, our_catalog())
    lifecycle.advance(run, scenario.kill_at)
    perform_solution(run, scenario)
    contact(run)
    verdict = evaluate(run)
    assert verdict.success is True, verdict.detail


@pytest.mark.parametrize("path", OUR_ACTIVE)
def test_our_active_scenario_fails_without_its_solution(path):
    scenario = ours(path)
    run = start(scenario, our_catalog())
    lifecycle.advance(run, scenario.kill_at)
    contact(run)
    assert evaluate(run).success is False


@pytest.mark.parametrize("path", OUR_NOOPS)
def test_our_noop_passes_when_the_agent_never_contacts(path):
    scenario = ours(path)
    run = start(scenario, our_catalog())
    lifecycle.advance(run, scenario.kill_at)
    assert evaluate(run).success is True


@pytest.mark.parametrize("path", OUR_NOOPS)
def test_our_noop_fails_when_the_agent_contacts(path):
    scenario = ours(path)
    run = start(scenario, our_catalog())
    lifecycle.advance(run, scenario.kill_at)
    perform_solution(run, scenario)
    contact(run)
    assert evaluate(run).success is False
