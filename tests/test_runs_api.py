"""The multi-run API, run URLs, isolation and the control token."""

from __future__ import annotations

import threading
import time

import pytest
from django.db import connection
from rest_framework.test import APIClient

from apps.tally.environment import tally_scenario
from events.models import Event, EventKind, Run

pytestmark = pytest.mark.django_db


@pytest.fixture
def api():
    return APIClient()


def create(api, **body):
    body.setdefault("scenario_json", tally_scenario())
    response = api.post("/api/runs/", body, format="json")
    assert response.status_code == 201, response.content
    return response.json()


def test_create_get_advance_evaluate_close(api):
    run = create(api, clock_mode="virtual")
    assert run["status"] == "ready"
    assert run["task_url"].endswith(f"/r/{run['token']}/start")
    assert run["contact_url"].endswith(f"/r/{run['token']}/contact")
    advanced = api.post(f"/api/runs/{run['id']}/advance/", {"time": 31}, format="json").json()
    assert [e["time"] for e in advanced["processed_events"]] == [10.0, 30.0]
    assert (
        api.post(f"/api/runs/{run['id']}/advance/", {"time": 3}, format="json").status_code == 400
    )
    assert api.get(f"/r/{run['token']}/contact").status_code == 200
    verdict = api.post(f"/api/runs/{run['id']}/evaluate/").json()
    assert verdict["success"] is True and verdict["run"] == run["id"]
    assert api.post(f"/api/runs/{run['id']}/close/").json()["closed_at"] is not None
    assert api.get(f"/r/{run['token']}/contact").status_code == 404
    assert any(r["id"] == run["id"] for r in api.get("/api/runs/").json())


@pytest.mark.parametrize(
    "body,needle",
    [
        ({"speed_factor": 8}, "above MAX_SPEED_FACTOR"),
        ({"speed_factor": 0}, "must be positive"),
        ({"clock_mode": "sundial"}, "clock_mode"),
        ({"scenario": "nope", "scenario_json": None}, "exactly one"),
        ({"scenario_json": {"id": "x"}}, "scenario_json"),
    ],
)
def test_bad_run_requests_are_4xx_naming_the_problem(api, body, needle):
    payload = {"scenario_json": tally_scenario(), **body}
    if payload.get("scenario_json") is None:
        payload.pop("scenario_json")
        payload["scenario_json"] = tally_scenario()
    response = api.post("/api/runs/", payload, format="json")
    assert 400 <= response.status_code < 500
    assert needle in response.json()["detail"]


def test_unknown_library_scenario_is_404(api):
    response = api.post("/api/runs/", {"scenario": "no-such-scenario"}, format="json")
    assert response.status_code in (400, 404)
    assert "no-such-scenario" in response.json()["detail"]


def test_task_url_starts_the_clock_once_and_reloads_harmlessly(api):
    run = create(api)
    first = api.get(f"/r/{run['token']}/start")
    assert first.status_code == 302 and first["Location"] == f"/r/{run['token']}/tally"
    started_at = Run.objects.get(pk=run["id"]).started_at
    assert api.get(f"/r/{run['token']}/start").status_code == 302
    assert Run.objects.get(pk=run["id"]).started_at == started_at
    assert api.get(f"/api/runs/{run['id']}/").json()["status"] == "running_auto"


def test_actions_over_http_are_validated_and_logged(api):
    run = create(api, clock_mode="virtual")
    url = f"/r/{run['token']}/actions"
    ok = api.post(url, {"action": "poke", "payload": {"n": 2}}, format="json")
    assert ok.status_code == 201 and ok.json()["action"] == "poke"
    assert api.post(url, {"action": "poke", "payload": {"n": -1}}, format="json").status_code == 400
    unknown = api.post(url, {"action": "kick", "payload": {}}, format="json")
    # A bad request naming the allowed actions, not a missing page.
    assert unknown.status_code == 400 and "allowed: poke" in unknown.json()["detail"]
    wrong_type = api.post(url, {"action": "poke", "payload": {"n": "two"}}, format="json")
    assert wrong_type.status_code == 400 and "'n'" in wrong_type.json()["detail"]


@pytest.mark.parametrize("clock_mode", ["live", "fast_forward"])
def test_advance_refuses_a_clock_that_moves_with_the_wall(api, clock_mode):
    """A live run's clock belongs to the wall: whoever could jump it (before its start, too)
    would choose the reaction time the run is graded on."""
    run = create(api, clock_mode=clock_mode)
    response = api.post(f"/api/runs/{run['id']}/advance/", {"time": 31}, format="json")
    assert response.status_code == 409
    assert (
        f"/advance moves only a virtual clock: run {run['id']} has a {clock_mode} clock"
        in (response.json()["detail"])
    )
    assert api.get(f"/api/runs/{run['id']}/").json()["status"] == "ready"  # untouched


@pytest.mark.django_db(transaction=True)
def test_twenty_concurrent_runs_are_isolated(api):
    runs = [create(api, clock_mode="virtual") for _ in range(20)]
    chosen = runs[7]
    errors = []

    def agent(run):
        try:
            client = APIClient()
            client.post(f"/api/runs/{run['id']}/advance/", {"time": 40}, format="json")
            if run is chosen:
                client.post(
                    f"/r/{run['token']}/actions",
                    {"action": "poke", "payload": {"n": 1}},
                    format="json",
                )
            client.get(f"/r/{run['token']}/contact")
        except BaseException as exc:
            errors.append(exc)
        finally:
            connection.close()  # kept ones would outlive the test database

    threads = [threading.Thread(target=agent, args=(r,)) for r in runs]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    for run in runs:
        actions = Event.objects.filter(run_id=run["id"], kind=EventKind.ACTION).count()
        assert actions == (1 if run is chosen else 0)
        verdict = api.post(f"/api/runs/{run['id']}/evaluate/").json()
        assert verdict["actions"] == actions
        assert verdict["success"] is True


def test_control_token_guards_control_endpoints_but_not_agent_urls(api, settings):
    run = create(api, clock_mode="virtual")
    settings.SENTINEL_CONTROL_TOKEN = "s3cret"
    for method, path in [
        ("get", "/api/runs/"),
        ("post", f"/api/runs/{run['id']}/evaluate/"),
        ("get", "/status"),
        ("post", "/init"),
        ("get", "/close"),
        ("post", "/evaluate"),
        ("post", "/dev_init?environment=tally"),
        ("get", "/api/schema/"),
    ]:
        assert getattr(api, method)(path).status_code == 403, path
        assert getattr(api, method)(path, HTTP_AUTHORIZATION="Bearer wrong").status_code == 403, (
            path
        )
    assert api.get("/api/runs/", HTTP_AUTHORIZATION="Bearer s3cret").status_code == 200
    assert api.get("/status", HTTP_X_SENTINEL_TOKEN="s3cret").status_code == 200
    # Agent-facing URLs still work without it.
    assert api.get(f"/r/{run['token']}/contact").status_code == 200
    assert api.post(f"/r/{run['token']}/contact", {"message": "hi"}).status_code == 200


def test_openapi_schema_is_served(api):
    response = api.get("/api/schema/")
    assert response.status_code == 200
    assert b"/api/runs/" in response.content


@pytest.mark.django_db(transaction=True)
def test_the_ticker_fires_a_live_run_without_any_request(api, running_ticker):
    run = create(
        api,
        scenario_json=tally_scenario(pings=[(0.0, 1), (0.4, 1), (1.2, 1)], condition_at=1.2),
        speed_factor=1.0,
    )
    api.post(f"/api/runs/{run['id']}/start/")
    deadline = time.monotonic() + 10
    fired = []
    while time.monotonic() < deadline and len(fired) < 2:
        time.sleep(0.05)
        fired = list(
            Event.objects.filter(
                run_id=run["id"], kind=EventKind.SCENARIO, lateness_ms__isnull=False
            ).values_list("timeline_index", flat=True)
        )
    # Fired by the ticker alone (no request touched the run), each exactly once, in order.
    assert fired == [1, 2]
