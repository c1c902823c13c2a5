"""The SentinelBench-compatible flat endpoints: every state transition and every 409 of §1–2."""

from __future__ import annotations

import pytest
from rest_framework.test import APIClient

from apps.tally.environment import tally_scenario

pytestmark = pytest.mark.django_db


@pytest.fixture
def api():
    return APIClient()


def init_body(**overrides) -> dict:
    scenario = tally_scenario(
        **{k: v for k, v in overrides.items() if k in ("condition_at", "pings", "eval_sql")}
    )
    body = {
        "environment": "tally",
        "event_timeline_end": scenario["event_timeline_end"],
        "eval_sql": scenario.get("eval_sql", ""),
        "condition_at": scenario["condition_at"],
        "events": scenario["events"],
        "start_page": scenario["start_page"],
    }
    body.update(
        {k: v for k, v in overrides.items() if k not in ("condition_at", "pings", "eval_sql")}
    )
    return body


def status_of(api) -> str:
    return api.get("/status").json()["status"]


def test_status_starts_in_preinit_and_close_is_idempotent(api):
    assert api.get("/status").json() == {
        "success": True,
        "status": "preinit",
        "simulation_time": 0,
        "next_event_time": None,
    }
    assert api.get("/close").json() == {"success": True, "status": "preinit"}


@pytest.mark.parametrize(
    "method,path",
    [
        ("get", "/advance?time=1"),
        ("get", "/play"),
        ("get", "/redirect"),
        ("get", "/contact"),
        ("post", "/contact"),
        ("post", "/evaluate"),
        ("get", "/data/config"),
    ],
)
def test_every_session_endpoint_is_409_before_init(api, method, path):
    response = getattr(api, method)(path)
    assert response.status_code == 409
    assert response.json()["detail"] == "No active simulation. Call /init first."


def test_init_moves_preinit_to_ready_and_fires_the_preload(api):
    body = api.post("/init", init_body(), format="json").json()
    assert body["success"] is True and body["status"] == "ready"
    assert body["simulation_time"] == 0
    assert body["next_event_time"] == 10.0
    second = api.post("/init", init_body(), format="json")
    assert second.status_code == 409
    assert "must be called in state 'preinit'" in second.json()["detail"]


def test_init_rejects_an_unknown_environment_listing_the_valid_names(api):
    response = api.post("/init", init_body(environment="nowhere"), format="json")
    assert response.status_code == 422
    assert "nowhere" in response.json()["detail"] and "tally" in response.json()["detail"]
    assert status_of(api) == "preinit"


@pytest.mark.parametrize(
    "speed_factor,needle",
    [(0, "must be positive"), (-1, "must be positive"), (8, "above MAX_SPEED_FACTOR")],
)
def test_init_rejects_speed_factors_outside_the_limits(api, speed_factor, needle):
    response = api.post("/init", init_body(speed_factor=speed_factor), format="json")
    assert response.status_code == 422
    assert needle in response.json()["detail"]


def test_advance_is_manual_monotonic_and_reports_processed_events(api):
    api.post("/init", init_body(), format="json")
    first = api.get("/advance?time=12").json()
    assert first["status"] == "running_manual"
    assert first["simulation_time"] == 12
    assert [e["time"] for e in first["processed_events"]] == [10.0]
    backwards = api.get("/advance?time=5")
    assert backwards.status_code == 400
    assert "backwards" in backwards.json()["detail"]
    assert api.get("/advance").status_code == 422
    assert api.get("/advance?time=40").json()["processed_events"][0]["time"] == 30.0


def test_play_starts_the_live_clock_and_locks_advance_out_after_contact(api):
    api.post("/init", init_body(), format="json")
    assert api.get("/play").json()["status"] == "running_auto"
    assert api.get("/play").status_code == 409
    assert api.get("/advance?time=1").status_code == 409
    assert api.get("/contact").status_code == 200
    assert status_of(api) == "completed"
    for path in ("/advance?time=1", "/play", "/redirect"):
        response = api.get(path)
        assert response.status_code == 409, path
        assert "Current: 'completed'" in response.json()["detail"]


def test_redirect_starts_the_clock_and_goes_to_the_run_pages_on_this_site(api):
    api.post("/init", init_body(), format="json")
    response = api.get("/redirect?frontend_url=https://evil.example/")
    assert response.status_code == 302
    assert response["Location"].startswith("/r/") and response["Location"].endswith("/tally")
    assert status_of(api) == "running_auto"
    assert api.get("/redirect").status_code == 409  # single use, as upstream


def test_contact_before_redirect_records_time_zero_and_locks_the_run(api):
    api.post("/init", init_body(), format="json")
    page = api.get("/contact")
    assert page.status_code == 200
    assert b'<textarea name="message"' in page.content and b"<title>Contact</title>" in page.content
    assert api.get("/redirect").status_code == 409
    thanks = api.post("/contact", {"message": "done"})
    assert b"Thank you for your message" in thanks.content
    verdict = api.post("/evaluate").json()
    assert verdict["contact_get_time"] == 0.0
    assert verdict["contact_message"] == "done"
    assert verdict["contact_post_time"] == 0.0


def test_evaluate_completes_the_run_and_close_returns_to_preinit(api):
    api.post("/init", init_body(), format="json")
    api.get("/advance?time=5")
    assert api.post("/evaluate").json()["success"] is False
    assert status_of(api) == "completed"
    assert api.post("/evaluate").status_code == 200  # may be called repeatedly
    assert api.get("/close").json()["status"] == "preinit"
    assert status_of(api) == "preinit"


def test_dev_init_validates_the_environment(api):
    response = api.post("/dev_init?environment=nowhere")
    assert response.status_code == 400
    assert "tally" in response.json()["detail"]
    assert api.post("/dev_init?environment=tally").status_code == 404  # no scenarios/tally/dev.json


def test_scenario_details_hide_the_answer_from_unauthenticated_callers(api, settings):
    ids = api.get("/scenarios").json()["scenarios"]
    if not ids:
        pytest.skip("no scenarios in the library yet")
    public = api.get(f"/scenarios/{ids[0]}").json()
    assert "eval_sql" not in public and "condition_at" not in public and "events" not in public
    settings.SENTINEL_CONTROL_TOKEN = "s3cret"
    full = api.get(f"/scenarios/{ids[0]}", HTTP_AUTHORIZATION="Bearer s3cret").json()
    assert "events" in full and "condition_at" in full
    assert api.get("/scenarios/does-not-exist").status_code == 404


def test_config_reports_the_environment_and_the_self_user(api):
    api.post("/init", init_body(speed_factor=2.0), format="json")
    config = api.get("/data/config").json()
    assert config["environment"] == "tally"
    assert config["event_timeline_end"] == 360.0
    assert config["speed_factor"] == 2.0
