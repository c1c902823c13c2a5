"""Scenario authoring in the admin: one source of truth with the files, checked eval_sql, the
reference panel and the start-a-run button (test client; the browser test follows an author)."""

from __future__ import annotations

import json
import re

import pytest

from apps.scenarios.models import Scenario
from events.models import Run
from tests.first_hour.admin_forms import change_form_data
from tests.first_hour.conftest import INBOX

pytestmark = pytest.mark.django_db

CHANGELIST = "/admin/scenarios/scenario/"


def change_url(path: str) -> str:
    return f"{CHANGELIST}{Scenario.objects.get(path=path).pk}/change/"


@pytest.fixture
def opened(admin_client, scenario_dir):
    """The admin lists the folder's scenarios without any manual import step."""
    assert Scenario.objects.count() == 0
    assert admin_client.get(CHANGELIST).status_code == 200
    assert Scenario.objects.count() == len(list(scenario_dir.glob("*/*.json")))
    return admin_client


def test_an_admin_edit_is_what_the_api_and_the_next_run_use(opened, api, scenario_dir):
    page = opened.get(change_url(INBOX))
    data = change_form_data(page)
    data["prompt"] = "Edited in the admin."
    response = opened.post(change_url(INBOX), data)
    assert response.status_code == 302, response.context["adminform"].form.errors
    on_disk = json.loads((scenario_dir / INBOX).read_text())
    assert on_disk["prompt"] == "Edited in the admin."
    spec = api.get("/api/scenarios/micromail-inbox-relative-passive/").json()
    assert spec["prompt"] == "Edited in the admin."
    run = api.post("/api/runs/", {"scenario": "micromail-inbox-relative-passive"}, format="json")
    assert run.json()["prompt"] == "Edited in the admin."


def test_a_broken_eval_sql_is_refused_on_save_with_the_reason_on_the_field(opened, scenario_dir):
    before = (scenario_dir / INBOX).read_text()
    for sql, reason in (
        ("SELEC COUNT(*) FROM emails", 'near "SELEC": syntax error'),
        ("SELECT COUNT(nope) FROM emails", "no such column: nope"),
    ):
        data = change_form_data(opened.get(change_url(INBOX)))
        data["eval_sql"] = sql
        response = opened.post(change_url(INBOX), data)
        assert response.status_code == 200
        errors = response.context["adminform"].form.errors["eval_sql"]
        assert reason in errors[0]
    assert (scenario_dir / INBOX).read_text() == before


def test_a_file_changed_on_disk_during_an_edit_is_reported_and_neither_is_overwritten(
    opened, scenario_dir
):
    data = change_form_data(opened.get(change_url(INBOX)))
    on_disk = json.loads((scenario_dir / INBOX).read_text())
    on_disk["prompt"] = "Changed on disk."
    (scenario_dir / INBOX).write_text(json.dumps(on_disk, indent=2) + "\n")
    data["prompt"] = "Changed in the admin."
    response = opened.post(change_url(INBOX), data)
    assert response.status_code == 200
    assert "changed on disk since this scenario was opened" in response.content.decode()
    assert json.loads((scenario_dir / INBOX).read_text())["prompt"] == "Changed on disk."
    # Reopening imports the file's version (the row was not edited).
    opened.get(change_url(INBOX))
    assert Scenario.objects.get(path=INBOX).prompt == "Changed on disk."


def test_a_new_file_on_disk_appears_and_a_deleted_one_goes(opened, scenario_dir):
    twin = json.loads((scenario_dir / INBOX).read_text())
    twin["id"] = "micromail-new-on-disk"
    (scenario_dir / "micromail/new-on-disk.json").write_text(json.dumps(twin))
    (scenario_dir / "micromail/cc-relative-active.json").unlink()
    html = opened.get(CHANGELIST).content.decode()
    assert "micromail-new-on-disk" in html and "1 new" in html and "1 removed" in html
    assert not Scenario.objects.filter(path="micromail/cc-relative-active.json").exists()


def test_the_change_page_has_a_working_start_button_and_the_reference(opened):
    html = opened.get(change_url(INBOX)).content.decode()
    # The start form must not sit inside the admin's form: browsers drop a nested form.
    start = html.index('id="scenario_form"')
    main_form = html[start : html.index("</form>", start)]
    assert 'id="start-run-form"' not in main_form and 'id="start-run-form"' in html
    assert 'form="start-run-form"' in main_form
    reference = html[html.index('id="scenario-reference"') :]
    assert re.search(r'data-environment="micromail" open', reference)
    assert "<code>new_email</code>" in reference and "<code>email_id</code>" in reference
    assert "<code>emails</code>" in reference and "<code>hasAttachment</code>" in reference


def test_start_a_run_from_the_change_page(opened):
    pk = Scenario.objects.get(path=INBOX).pk
    response = opened.post(f"{CHANGELIST}{pk}/start-run/")
    run = Run.objects.get()
    assert response.status_code == 302 and response["Location"] == f"/r/{run.token}/start"


def test_replay_of_an_ungraded_run_says_so(admin_client, api, scenario_dir):
    run = api.post("/api/runs/", {"scenario": "micromail-inbox-relative-passive"}, format="json")
    response = admin_client.post(
        "/admin/events/run/",
        {"action": "replay_runs", "_selected_action": [run.json()["id"]]},
        follow=True,
    )
    html = response.content.decode()
    assert "not graded yet" in html and "mismatch" not in html


def test_a_moved_scenario_leaves_no_copy_behind(opened, scenario_dir):
    data = change_form_data(opened.get(change_url(INBOX)))
    data["path"] = "micromail/inbox-moved.json"
    response = opened.post(change_url("micromail/inbox-relative-passive.json"), data)
    assert response.status_code == 302
    assert not (scenario_dir / INBOX).exists()
    assert (scenario_dir / "micromail/inbox-moved.json").is_file()
    opened.get(CHANGELIST)  # imports the folder again: one row, at the new path
    assert Scenario.objects.filter(scenario_id="micromail-inbox-relative-passive").count() == 1
