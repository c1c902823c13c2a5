"""The scenario admin: filters, chart, dry run, timeline validation and actions (test client)."""

from __future__ import annotations

import io

import pytest
from django.core.management import call_command

from apps.scenarios.admin import TimelineEventForm
from apps.scenarios.models import Scenario
from events.models import Run
from tests.conftest import OUR_SCENARIOS

pytestmark = pytest.mark.django_db

INBOX = "micromail/inbox-relative-passive.json"


@pytest.fixture
def scenarios(own_scenarios):
    call_command("loadscenarios", str(OUR_SCENARIOS), stdout=io.StringIO(), stderr=io.StringIO())
    return Scenario.objects.all()


def changelist(client, query="") -> str:
    return client.get(f"/admin/scenarios/scenario/{query}").content.decode()


def test_list_filters_by_action_requirement_criterion_and_noop(scenarios, admin_client):
    passive = changelist(admin_client, "?monitoring_approach__exact=passive")
    assert "micromail-inbox-relative-passive" in passive and "relative-active" not in passive
    noop = changelist(admin_client, "?noop=yes")
    assert (
        "micromail-sender-absolute-noop" in noop and "micromail-inbox-relative-passive" not in noop
    )
    relative = changelist(admin_client, "?milestone_type__exact=relative")
    assert "micromail-cc-relative-active" in relative and "absolute-passive" not in relative


def test_search_by_prompt_and_by_id(scenarios, admin_client):
    assert "micromail-inbox-relative-passive" in changelist(admin_client, "?q=5+new+emails+appear")
    assert "micromail-junk-relative-passive" in changelist(admin_client, "?q=junk-relative")


def test_the_change_form_shows_the_chart_and_the_dry_run_button(scenarios, admin_client):
    scenario = scenarios.get(path=INBOX)
    html = admin_client.get(f"/admin/scenarios/scenario/{scenario.pk}/change/").content.decode()
    assert (
        'id="timeline-chart"' in html
        and 'class="condition-at"' in html
        and 'class="kill-at"' in html
    )
    assert 'name="_dryrun"' in html


def test_the_dry_run_page_warns_when_condition_at_is_off(scenarios, admin_client):
    scenario = scenarios.get(path=INBOX)
    ok = admin_client.get(f"/admin/scenarios/scenario/{scenario.pk}/dry-run/").content.decode()
    assert 'id="dry-run-ok"' in ok and 'id="dry-run-table"' in ok
    Scenario.objects.filter(pk=scenario.pk).update(condition_at=203.64)
    html = admin_client.get(f"/admin/scenarios/scenario/{scenario.pk}/dry-run/").content.decode()
    assert "first holds at 173.64 s, but condition_at is 203.64 s" in html
    assert 'id="timeline-chart"' in html


def test_timeline_entries_get_type_choices_and_catalog_checks():
    form_class = type("F", (TimelineEventForm,), {"environment": "micromail"})
    form = form_class(
        data={"position": 1, "time": 10, "type": "new_email", "payload": '{"email_id": "nope"}'}
    )
    assert not form.is_valid()
    assert "not in catalog table 'emails': nope" in form.errors["payload"][0]
    assert [c for c, _ in form.fields["type"].choices] == [
        "new_email",
        "preload_emails",
        "recall_email",
    ]
    good = form_class(
        data={"position": 1, "time": 10, "type": "new_email", "payload": '{"email_id": "base-04"}'}
    )
    assert good.is_valid(), good.errors


def test_export_downloads_the_file_byte_identical(scenarios, admin_client):
    scenario = scenarios.get(path=INBOX)
    response = admin_client.get(f"/admin/scenarios/scenario/{scenario.pk}/export/")
    assert response["Content-Disposition"] == 'attachment; filename="inbox-relative-passive.json"'
    assert response.content == (OUR_SCENARIOS / INBOX).read_bytes()


def test_duplicate_copies_the_timeline(scenarios, admin_client):
    scenario = scenarios.get(path=INBOX)
    admin_client.post(
        "/admin/scenarios/scenario/", {"action": "duplicate", "_selected_action": [scenario.pk]}
    )
    copy = Scenario.objects.get(path="micromail/inbox-relative-passive-copy.json")
    assert copy.scenario_id == "micromail-inbox-relative-passive-copy"
    assert copy.timeline.count() == scenario.timeline.count()


def test_start_a_run_opens_its_task_url(scenarios, admin_client):
    scenario = scenarios.get(path=INBOX)
    response = admin_client.post(
        "/admin/scenarios/scenario/", {"action": "start_run", "_selected_action": [scenario.pk]}
    )
    run = Run.objects.get(scenario_id="micromail-inbox-relative-passive")
    assert response.status_code == 302 and response["Location"] == f"/r/{run.token}/start"
    assert run.scenario["condition_at"] == 173.64


def test_the_admin_is_staff_only(scenarios, client):
    scenario = scenarios.get(path=INBOX)
    for url in ("/admin/scenarios/scenario/", f"/admin/scenarios/scenario/{scenario.pk}/dry-run/"):
        response = client.get(url)
        assert response.status_code == 302 and "/admin/login/" in response["Location"]


def test_the_timeline_editor_says_what_each_event_type_takes(scenarios, admin_client):
    scenario = Scenario.objects.get(path=INBOX)
    html = admin_client.get(f"/admin/scenarios/scenario/{scenario.pk}/change/").content.decode()
    assert "preload_emails: Mail already in the mailbox at the start" in html
    assert "email_ids (list of strings)" in html and "email_id (string)" in html
