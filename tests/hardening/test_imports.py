"""An imported run is checked as one made through the API (finding: import_run accepted a
scenario that was a string, an unknown environment, list payloads, speed 0 and NUL characters,
after which the run list answered 500 for everyone and replay crashed; and it followed a
catalog_dir anywhere on the disk). A bad file is one line naming it, and changes nothing."""

from __future__ import annotations

import json

import pytest
from rest_framework.test import APIClient

from apps.replay.transfer import TransferError, export_lines, import_lines
from apps.scenarios.library import get_scenario
from events import lifecycle
from events.models import Run

pytestmark = pytest.mark.django_db


@pytest.fixture
def exported() -> list[dict]:
    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    return [json.loads(line) for line in export_lines(run)]


def lines(records: list[dict]) -> list[str]:
    return [json.dumps(record) for record in records]


def header(records, **changes):
    records[0]["run"].update(changes)
    return records


def first_event(records, **changes):
    """The first scenario event (the preload) changed."""
    next(r for r in records[1:] if r["kind"] == "scenario").update(changes)
    return records


@pytest.mark.parametrize(
    "spoil,named",
    [
        (lambda r: header(r, scenario="a string"), "run.scenario"),
        (lambda r: header(r, scenario={**r[0]["run"]["scenario"], "environment": "microspace"}), "microspace"),
        (lambda r: header(r, speed_factor=0), "speed_factor"),
        (lambda r: header(r, status="exploded"), "'status'"),
        (lambda r: header(r, sim_time="late"), "'sim_time'"),
        (lambda r: first_event(r, payload=[1, 2]), "'payload'"),
        (lambda r: first_event(r, payload={"email_ids": ["a\x00b"]}), "NUL"),
        (lambda r: first_event(r, kind="magic"), "'kind'"),
        (lambda r: first_event(r, type="no_such_event"), "no_such_event"),
        (lambda r: first_event(r, seq=7), "seq"),
    ],
    ids=["scenario-text", "environment", "speed-0", "status", "sim-time", "list-payload", "nul",
         "kind", "type", "seq"],
)  # fmt: skip
def test_a_bad_import_names_its_problem_and_changes_nothing(exported, spoil, named):
    before = Run.objects.count()
    with pytest.raises(TransferError) as refused:
        import_lines(lines(spoil(exported)))
    assert named in str(refused.value) and "\n" not in str(refused.value)
    assert Run.objects.count() == before
    assert APIClient().get("/api/runs/").status_code == 200


def test_an_import_never_reads_a_catalog_folder_the_server_does_not_play(exported, tmp_path):
    (tmp_path / "emails.json").write_text("[]")
    run, warnings = import_lines(lines(header(exported, catalog_dir=str(tmp_path))))
    assert run.catalog_dir != str(tmp_path)
    assert any("does not play" in warning for warning in warnings)


def test_a_good_import_still_imports(exported):
    run, warnings = import_lines(lines(exported))
    assert run.is_closed and run.events.count() == len(exported) - 1 and warnings == []
