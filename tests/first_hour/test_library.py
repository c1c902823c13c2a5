"""One bad scenario file never takes the library down; a repeated id runs by its path."""

from __future__ import annotations

import io
import json

import pytest
from django.core.management import CommandError, call_command

from apps.scenarios.library import get_scenario, library
from tests.conftest import UPSTREAM
from tests.first_hour.conftest import INBOX, JUNK

pytestmark = pytest.mark.django_db

UPSTREAM_DUPLICATE = "microfy/public-playlists-relative-passive.json"


@pytest.fixture
def broken_dir(scenario_dir):
    """One file failing validation, and one repeating the inbox scenario's id."""
    bad = json.loads((scenario_dir / JUNK).read_text())
    bad["kill_at"] = -1
    (scenario_dir / JUNK).write_text(json.dumps(bad))
    twin = json.loads((scenario_dir / INBOX).read_text())
    twin["prompt"] = "The twin: same id, another file."
    (scenario_dir / "micromail/twin.json").write_text(json.dumps(twin))
    return scenario_dir


def test_the_rest_loads_and_each_bad_file_is_reported_with_its_reason(broken_dir):
    loaded = library()
    problems = {problem.path: problem for problem in loaded.problems}
    assert set(problems) == {JUNK, "micromail/twin.json"}
    assert "kill_at" in problems[JUNK].detail
    assert problems["micromail/twin.json"].duplicate_of == INBOX
    files = [p for p in broken_dir.glob("*/*.json") if p.name != "dev.json"]
    assert len(loaded.by_path) == len(files) - 1  # all but the invalid one, the twin included
    assert (
        get_scenario("micromail-inbox-relative-passive").prompt
        != "The twin: same id, another file."
    )
    assert get_scenario("micromail/twin.json").prompt == "The twin: same id, another file."


def test_the_api_lists_the_problems_and_runs_both_files_of_a_repeated_id(broken_dir, api):
    listing = api.get("/api/scenarios/")
    assert listing.status_code == 200
    by_path = {entry["path"]: entry for entry in listing.json()}
    assert by_path[JUNK]["id"] is None and "kill_at" in by_path[JUNK]["error"]
    assert by_path["micromail/twin.json"]["duplicate_of"] == INBOX
    assert api.get("/api/scenarios/micromail/twin.json/").json()["prompt"].startswith("The twin")
    for reference in ("micromail-inbox-relative-passive", "micromail/twin.json"):
        created = api.post("/api/runs/", {"scenario": reference}, format="json")
        assert created.status_code == 201, created.json()
    assert api.post("/api/runs/", {"scenario": JUNK}, format="json").status_code == 404


def test_checkscenarios_names_each_bad_file_and_fails_only_for_invalid_ones(broken_dir):
    out = io.StringIO()
    with pytest.raises(CommandError, match="1 scenario file"):
        call_command("checkscenarios", stdout=out)
    lines = out.getvalue().splitlines()
    assert any(line.startswith(f"invalid: {JUNK}: ") and "kill_at" in line for line in lines)
    assert any(line.startswith("duplicate: micromail/twin.json: ") for line in lines)
    (broken_dir / JUNK).unlink()
    call_command("checkscenarios", stdout=io.StringIO())  # a repeated id alone is not an error


def test_an_edited_file_is_seen_at_the_next_request(scenario_dir, api):
    path = scenario_dir / INBOX
    data = json.loads(path.read_text())
    data["prompt"] = "Edited on disk."
    path.write_text(json.dumps(data) + "\n")
    spec = api.get("/api/scenarios/micromail-inbox-relative-passive/").json()
    assert spec["prompt"] == "Edited on disk."


@pytest.mark.upstream
def test_the_original_benchmark_folder_runs_as_it_is(settings, api):
    if not (UPSTREAM / "scenarios").is_dir():
        pytest.skip("original SentinelBench data absent (README, Conformance tests)")
    settings.SENTINEL_SCENARIO_DIR = UPSTREAM / "scenarios"
    listing = api.get("/api/scenarios/")
    assert listing.status_code == 200
    entries = listing.json()
    assert len(entries) == 109 and not [e for e in entries if e["id"] is None]
    twin = next(e for e in entries if e["path"] == UPSTREAM_DUPLICATE)
    assert twin["duplicate_of"] == "microfy/playlists-relative-passive.json"
    detail = api.get(f"/api/scenarios/{UPSTREAM_DUPLICATE}/")
    assert detail.status_code == 200 and detail.json()["environment"] == "microfy"
