"""An imported run is checked as one made through the API (finding: import_run accepted a
scenario that was a string, an unknown environment, list payloads, speed 0 and NUL characters,
after which the run list answered 500 for everyone and replay crashed; and it followed a
catalog_dir anywhere on the disk; and it took logged payloads that matched no schema, e.g. a
MicroMail `mark_read` of {"bogus": 1}, whose replay raised KeyError 'email_id'). A bad file is
one line naming it, and changes nothing."""

from __future__ import annotations

import json

import pytest
from rest_framework.test import APIClient

from apps.kit.fields import TEXT_CHARS
from apps.kit.links import environment_root
from apps.replay.transfer import TransferError, export_lines, import_lines
from apps.scenarios.library import get_scenario
from events import lifecycle
from events.commands import perform_action
from events.models import Run
from events.projection import fold_from_scratch
from tests.environments.folds import canonical

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


def logged(records, kind: str, type_: str, payload) -> list[dict]:
    """`records` with one more event at their end, as a file may say it was logged."""
    last = records[-1]
    extra = {"timeline_index": None, "lateness_ms": None}
    return [*records, {**last, **extra, "seq": last["seq"] + 1, "kind": kind, "type": type_, "payload": payload}]  # fmt: skip


DRAFT = {"to": ["a@example.com"], "subject": "s"}


@pytest.mark.parametrize(
    "kind,type_,payload,named",
    [
        ("action", "mark_read", {"bogus": 1}, "'email_id' is required"),  # the audit's file
        ("action", "save_draft", {**DRAFT, "body": "x" * (TEXT_CHARS + 1)}, "'body' must have at most"),
        ("action", "flag", {"email_id": 7}, "'email_id' must be string"),
        # Its schema's fields are all there, but not the id its `decide` adds: replay needs it.
        ("action", "send", DRAFT, "cannot be replayed: its payload has no field"),
        ("scenario", "new_email", {"subject": 1}, "new_email"),
        ("lifecycle", "contact_post", {"message": 3}, "'message' must be string"),
        ("lifecycle", "contact_post", {"message": "x" * (TEXT_CHARS + 1)}, "'message' must have at most"),
        ("lifecycle", "start", {}, "'started_at' is required"),
        ("lifecycle", "skip", {"from": 0, "to": 5, "why": "bored"}, "'why'"),
        ("lifecycle", "explode", {}, "lifecycle type 'explode'"),
        ("view", "page", {"path": ["/"]}, "'path' must be string"),
        ("view", "page", {"path": "/", "note": "hi"}, "note"),
        ("view", "glance", {"path": "/"}, "view type 'glance'"),
    ],
    ids=["audit-file", "long-body", "wrong-type", "derived-field", "scenario",
         "contact-type", "contact-length", "start", "skip", "lifecycle-type", "view-path",
         "view-field", "view-type"],
)  # fmt: skip
def test_an_event_that_fits_no_schema_is_refused_by_its_line(exported, kind, type_, payload, named):
    records = logged(exported, kind, type_, payload)
    before = Run.objects.count()
    with pytest.raises(TransferError) as refused:
        import_lines(lines(records))
    message = str(refused.value)
    assert message.startswith(f"line {len(records)}: ") and f"'{type_}'" in message
    assert named in message and "\n" not in message
    assert Run.objects.count() == before
    assert APIClient().get("/api/runs/").status_code == 200


def test_a_run_with_every_kind_of_entry_imports_and_replays_as_it_was_played():
    from django.test import Client

    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    client = Client()
    client.get(f"/r/{run.token}/start")  # the clock starts
    client.get(f"{environment_root(run)}/?folder=inbox")  # a view
    perform_action(run, "send", {**DRAFT, "body": "hello"})  # an id decided
    perform_action(run, "mark_read", {"email_id": "base-04"})
    client.post(f"/r/{run.token}/contact", {"message": "done"})
    lifecycle.close(run)
    imported, warnings = import_lines(export_lines(run))
    assert warnings == []
    assert canonical(fold_from_scratch(imported).state) == canonical(fold_from_scratch(run).state)


def test_the_lifecycle_schemas_know_every_clock_and_every_reason_to_stop_a_skip():
    from typing import get_args

    from apps.kit.log_payloads import ClockModeName, SkipReason
    from events import fastforward
    from events.models import ClockMode

    assert set(get_args(ClockModeName)) == set(ClockMode.values)
    reasons = (fastforward.SLEPT, fastforward.CHANGE, fastforward.TIMEOUT, fastforward.KILL_AT)
    assert set(get_args(SkipReason)) == set(reasons)
