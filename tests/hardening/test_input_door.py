"""Every input is checked at the door (findings 6–9): a bad value is a 4xx naming the field, and
nothing accepted can later make a page, an event list, an evaluation or the run list fail.

Runs on SQLite and on PostgreSQL alike (PostgreSQL refuses NUL in text and in jsonb, which used
to surface as 500s there).
"""

from __future__ import annotations

import json

import pytest
from django.test import Client
from rest_framework.test import APIClient

from apps.kit.links import environment_root, live_path
from apps.scenarios.library import get_scenario
from apps.tally.environment import tally_scenario
from events import lifecycle
from events.evaluation import evaluate
from events.models import ClockMode, Event, Run, RunStatus

pytestmark = pytest.mark.django_db

MAIL_SCENARIO = "micromail-inbox-relative-passive"


@pytest.fixture
def api():
    return APIClient()


def post_json(client, path: str, text: str | bytes):
    return client.post(path, data=text, content_type="application/json")


def detail(response) -> str:
    return response.json()["detail"]


def tally_init(**changes) -> dict:
    scenario = tally_scenario()
    body = {
        "environment": "tally",
        "event_timeline_end": scenario["event_timeline_end"],
        "eval_sql": scenario["eval_sql"],
        "condition_at": scenario["condition_at"],
        "events": scenario["events"],
    }
    return {**body, **changes}


def mail_run() -> Run:
    return lifecycle.create_run(get_scenario(MAIL_SCENARIO).to_run_spec())


def everything_still_answers(api, run: Run) -> None:
    """The run's pages, log and grading, and the run list, all still work."""
    assert api.get("/api/runs/").status_code == 200
    assert api.get(f"/api/runs/{run.pk}/").status_code == 200
    assert api.get(f"/api/runs/{run.pk}/events/").status_code == 200
    assert Client().get(environment_root(run) + "/").status_code == 200
    assert api.post(f"/api/runs/{run.pk}/evaluate/").status_code == 200


# --- finding 6: non-finite numbers ------------------------------------------------------------


@pytest.mark.parametrize("time", ["inf", "1e400", "-inf", "nan", "Infinity", "1e308"])
def test_finding_6_advance_to_a_non_finite_time_is_refused(api, time):
    assert api.post("/init", tally_init(speed_factor=4), format="json").status_code == 200
    response = api.get(f"/advance?time={time}")  # 1e308 × speed 4 overflows to infinity
    assert response.status_code == 422
    assert "time" in detail(response) and "finite" in detail(response)
    assert api.get("/status").status_code == 200
    assert api.post("/evaluate").status_code == 200
    assert api.get("/api/runs/").status_code == 200


def test_finding_6_the_api_refuses_non_finite_numbers_in_json(api):
    run = lifecycle.create_run(tally_scenario_spec(), clock_mode=ClockMode.VIRTUAL)
    for text in ('{"time": 1e400}', '{"time": Infinity}', '{"time": NaN}'):
        response = post_json(api, f"/api/runs/{run.pk}/advance/", text)
        assert response.status_code == 400, text
    response = api.post(f"/api/runs/{run.pk}/advance/", {"time": "inf"})  # a form: JSON only
    assert response.status_code == 415 and "multipart/form-data" in detail(response)
    for text in (
        '{"scenario": "x", "speed_factor": 1e400}',
        '{"scenario": "x", "speed_factor": NaN}',
    ):
        assert post_json(api, "/api/runs/", text).status_code == 400, text
    everything_still_answers(api, run)


def test_finding_6_the_run_list_never_fails_because_of_one_run(api):
    broken = lifecycle.create_run(tally_scenario_spec(), clock_mode=ClockMode.VIRTUAL)
    # A clock recorded as infinite before /advance refused it.
    Run.objects.filter(pk=broken.pk).update(sim_time=float("inf"), status=RunStatus.RUNNING_MANUAL)
    response = api.get("/api/runs/")
    assert response.status_code == 200
    assert {row["id"]: row["sim_time"] for row in response.json()}[broken.pk] is None


def tally_scenario_spec() -> dict:
    from apps.scenarios.format import parse_scenario

    return parse_scenario(tally_scenario(), source="tests").to_run_spec()


# --- finding 7: timeline entries checked against their schemas --------------------------------


@pytest.mark.parametrize(
    "entry,named",
    [
        ({"time": 1, "type": "new_email", "payload": {}}, "email_id"),
        ({"time": 1, "type": "no_such_type", "payload": {}}, "no_such_type"),
        ({"time": 1, "type": "new_email", "payload": {"email_id": 5}}, "email_id"),
        ({"time": 0, "type": "preload_emails", "payload": {"email_ids": "abc"}}, "email_ids"),
        ({"time": 1, "type": "new_email", "payload": {"email_id": "a", "x": 1}}, "x"),
    ],
)
def test_finding_7_init_checks_timeline_entries_as_scenario_files_are(api, entry, named):
    body = {"environment": "micromail", "event_timeline_end": 60, "events": [entry]}
    response = api.post("/init", body, format="json")
    assert response.status_code == 422
    assert "events[0]" in detail(response) and named in detail(response)
    assert api.get("/status").json()["status"] == "preinit"


def test_finding_7_a_valid_unsorted_timeline_is_sorted_as_upstream_does(api):
    events = [
        {"time": 5, "type": "new_email", "payload": {"email_id": "budget-review"}},
        {"time": 0, "type": "preload_emails", "payload": {"email_ids": []}},
    ]
    body = {"environment": "micromail", "event_timeline_end": 60, "events": events}
    assert api.post("/init", body, format="json").status_code == 200
    run = Run.objects.get(is_default_slot=True, closed_at__isnull=True)
    assert [e["time"] for e in run.timeline] == [0.0, 5.0]
    lifecycle.advance(run, 10)
    everything_still_answers(api, run)


# --- finding 8: text that cannot be stored or shown --------------------------------------------


@pytest.mark.parametrize("escape", ["\\ud800", "\\u0000", "\\udfff"])
def test_finding_8_a_sent_body_with_a_lone_surrogate_or_nul_is_refused(api, escape):
    run = mail_run()
    text = (
        '{"action": "send", "payload": {"to": ["ana@example.com"], "subject": "s", '
        f'"body": "x{escape}y"}}}}'
    )
    response = post_json(Client(), f"/r/{run.token}/actions", text)
    assert response.status_code == 400
    assert "payload.body" in detail(response)
    everything_still_answers(api, run)
    assert Client().get(environment_root(run) + "/?folder=sent").status_code == 200


def test_finding_8_the_payload_schemas_refuse_such_text_from_any_source(api):
    """Forms and scenario files reach the same check: the payload schema (events.schemas)."""
    from events.commands import perform_action
    from events.registry import ActionRejected

    run = mail_run()
    payload = {"to": ["ana@example.com"], "subject": "s\x00", "body": "b"}
    with pytest.raises(ActionRejected, match="payload field 'subject' contains a NUL"):
        perform_action(run, "send", payload)
    everything_still_answers(api, run)
    assert evaluate(run).detail  # grading works


def test_finding_8_a_contact_message_with_nul_is_refused(api):
    run = mail_run()
    response = Client().post(f"/r/{run.token}/contact", {"message": "done\x00"})
    assert response.status_code == 400
    assert not Event.objects.filter(run_id=run.pk, type="contact_post").exists()
    everything_still_answers(api, run)


# --- finding 9: input errors are 4xx, not 500 ---------------------------------------------------


def test_finding_9_deeply_nested_json_is_a_400(api):
    run = mail_run()
    for depth in (100_000, 40):
        text = "[" * depth + "]" * depth
        response = post_json(api, "/api/runs/", text)
        assert response.status_code == 400 and "nested" in detail(response)
        response = post_json(Client(), f"/r/{run.token}/actions", text)
        assert response.status_code == 400 and "nested" in detail(response)


def test_finding_9_invalid_utf8_is_a_400(api):
    run = mail_run()
    response = post_json(Client(), f"/r/{run.token}/actions", b'{"action": "\xff\xfe"}')
    assert response.status_code == 400 and "UTF-8" in detail(response)
    assert post_json(api, "/api/runs/", b'{"scenario": "\xff"}').status_code == 400


@pytest.mark.parametrize("url", ["http://[::1", "/r/x\x00", "x" * 5000, ""])
def test_finding_9_a_bad_live_url_is_a_400(url):
    run = mail_run()
    response = Client().get(live_path(run), {"url": url, "seq": 0})
    assert response.status_code == 400
    assert detail(response).startswith("url: ")


def test_finding_9_nul_anywhere_in_a_scenario_is_a_400_naming_the_field(api):
    scenario = tally_scenario()
    scenario["prompt"] = "Tell me\x00"
    response = post_json(api, "/api/runs/", json.dumps({"scenario_json": scenario}))
    assert response.status_code == 400
    assert "scenario_json.prompt" in detail(response) and "NUL" in detail(response)


def test_finding_9_an_over_long_scenario_id_is_a_400(api):
    scenario = tally_scenario(scenario_id="s" * 10_000)
    response = post_json(api, "/api/runs/", json.dumps({"scenario_json": scenario}))
    assert response.status_code == 400
    assert "id" in detail(response) and "200 characters" in detail(response)
    response = post_json(api, "/api/runs/", json.dumps({"scenario": "s" * 10_000}))
    assert response.status_code == 400


def test_a_page_of_another_environment_under_a_run_is_a_404():
    run = lifecycle.create_run(tally_scenario_spec())
    assert Client().get(f"/r/{run.token}/micromail/").status_code == 404
    assert Client().get(f"/r/{run.token}/tally/").status_code == 200
