"""export_run → import_run → replay: a faithful copy matches; a tampered log does not."""

from __future__ import annotations

import io
import json

import pytest
from django.core.management import call_command
from django.core.management.base import CommandError
from django.db import connection

from events.models import Event, Run

pytestmark = pytest.mark.django_db


def run_command(*args) -> str:
    out = io.StringIO()
    call_command(*args, stdout=out, stderr=io.StringIO())
    return out.getvalue()


def exported(run, tmp_path):
    path = tmp_path / "run.jsonl"
    path.write_text(run_command("export_run", str(run.pk)))
    return path


def test_export_starts_with_the_run_header_then_one_line_per_event(finished_run, tmp_path):
    lines = exported(finished_run, tmp_path).read_text().splitlines()
    header = json.loads(lines[0])
    assert header["run"]["scenario"] == finished_run.scenario
    assert header["run"]["speed_factor"] == 1.0 and header["run"]["clock_mode"] == "virtual"
    assert header["run"]["catalog_hash"] == finished_run.catalog_hash
    assert header["verdict"]["success"] is True
    assert [json.loads(line)["seq"] for line in lines[1:]] == list(
        Event.objects.filter(run=finished_run).values_list("seq", flat=True)
    )


def test_an_imported_run_replays_to_the_recorded_verdict_and_state(finished_run, tmp_path):
    new_id = int(run_command("import_run", str(exported(finished_run, tmp_path))).strip())
    copy = Run.objects.get(pk=new_id)
    assert copy.pk != finished_run.pk and copy.token != finished_run.token and copy.is_closed
    assert "match:" in run_command("replay", str(new_id))


def test_replay_of_the_original_run_matches_too(finished_run, tmp_path):
    exported(finished_run, tmp_path)  # records the verdict
    assert "match:" in run_command("replay", str(finished_run.pk))


def test_a_tampered_event_row_is_a_mismatch(finished_run, tmp_path):
    new_id = int(run_command("import_run", str(exported(finished_run, tmp_path))).strip())
    flag = Event.objects.get(run_id=new_id, kind="action", type="flag")
    with (
        connection.cursor() as cursor
    ):  # the ORM refuses updates: go around it, as an attacker would
        cursor.execute(
            "UPDATE events_event SET payload = %s WHERE id = %s",
            [json.dumps({"email_id": "team-lunch"}), flag.pk],
        )
    with pytest.raises(CommandError) as caught:
        run_command("replay", str(new_id))
    assert "mismatch" in str(caught.value) and "state digest" in str(caught.value)


def test_a_tampered_preload_changes_the_verdict(finished_run, tmp_path):
    new_id = int(run_command("import_run", str(exported(finished_run, tmp_path))).strip())
    late = Event.objects.get(run_id=new_id, kind="scenario", type="new_email")
    with connection.cursor() as cursor:
        cursor.execute(
            "UPDATE events_event SET payload = %s WHERE id = %s",
            [json.dumps({"email_id": "no-such-email"}), late.pk],
        )
    with pytest.raises(CommandError, match="verdict: recorded True, replayed False"):
        run_command("replay", str(new_id))


def test_import_rejects_a_file_without_header(tmp_path):
    path = tmp_path / "bad.jsonl"
    path.write_text('{"run": 1}\n')
    with pytest.raises(CommandError, match="line 1: field 'format'"):
        run_command("import_run", str(path))


def test_import_says_what_a_bare_log_lacks(tmp_path):
    path = tmp_path / "events.jsonl"
    path.write_text('{"seq": 1}\n')
    with pytest.raises(CommandError, match="line 1: an event, not a run header: this log has no"):
        run_command("import_run", str(path))


def test_unknown_run_is_a_one_line_error():
    with pytest.raises(CommandError, match="run '999999' not found"):
        run_command("replay", "999999")


def test_a_run_without_a_record_does_not_match_until_one_is_recorded(finished_run):
    with pytest.raises(CommandError, match="no recorded verdict"):
        run_command("replay", str(finished_run.pk))
    assert "match:" in run_command("replay", "--record", str(finished_run.pk))
