"""The agent's side of fast-forward: `POST /r/<token>/wait` (apps/control/agent.py)."""

from __future__ import annotations

import pytest
from django.test import Client
from rest_framework.test import APIClient

from apps.tally.environment import tally_scenario
from events.models import Event, EventKind

pytestmark = pytest.mark.django_db


@pytest.fixture
def api():
    return APIClient()


@pytest.fixture
def agent():
    return Client()


def started(api, agent, clock_mode: str = "fast_forward") -> dict:
    """A tally run (pings at 0, 10, 30, 50 s) whose agent has opened its task URL."""
    response = api.post(
        "/api/runs/", {"scenario_json": tally_scenario(), "clock_mode": clock_mode}, format="json"
    )
    assert response.status_code == 201, response.content
    run = response.json()
    assert run["wait_url"].endswith(f"/r/{run['token']}/wait")
    if clock_mode != "virtual":
        assert agent.get(run["task_url"]).status_code == 302  # starts the clock
    return run


def wait(agent, run: dict, body) -> tuple[int, dict]:
    response = agent.post(run["wait_url"], body, content_type="application/json")
    return response.status_code, response.json()


def test_a_sleep_answers_the_new_time_and_what_fired(api, agent):
    run = started(api, agent)
    status, answer = wait(agent, run, {"seconds": 35})
    assert status == 200, answer
    assert answer["why"] == "slept"
    assert answer["sim_time"] == pytest.approx(answer["from"] + 35)
    assert [fired["at"] for fired in answer["fired"]] == [10.0, 30.0]
    assert (
        answer["seq"]
        == Event.objects.filter(run_id=run["id"])
        .exclude(kind__in=(EventKind.VIEW, EventKind.LIFECYCLE))
        .order_by("-seq")
        .values_list("seq", flat=True)
        .first()
    )
    assert answer["run_status"] == "running_auto"
    # The agent's pages show the new moment: the third ping is on the tally page.
    assert api.get(f"/api/runs/{run['id']}/").json()["sim_time"] >= answer["sim_time"]


def test_until_change_wakes_at_the_next_entry(api, agent):
    run = started(api, agent)
    status, answer = wait(agent, run, {"until": "change", "timeout": 100})
    assert status == 200, answer
    assert (answer["sim_time"], answer["why"]) == (10.0, "change")
    assert [fired["type"] for fired in answer["fired"]] == ["ping"]
    status, answer = wait(agent, run, {"until": "change", "timeout": 5})
    assert (answer["why"], answer["fired"]) == ("timeout", [])
    assert answer["sim_time"] == pytest.approx(answer["from"] + 5)


def test_a_change_since_the_agents_last_look_answers_at_once(api, agent):
    run = started(api, agent)
    status, answer = wait(agent, run, {"seconds": 10.5})  # the ping at 10 fires on the way
    assert (status, answer["why"]) == (200, "slept")
    looked = answer["sim_time"]
    # Since a moment before the ping: it is the change, it has come, the clock stays.
    status, answer = wait(agent, run, {"until": "change", "timeout": 100, "since": 9.0})
    assert (status, answer["why"], answer["fired"]) == (200, "change", [])
    assert answer["sim_time"] == answer["from"] == pytest.approx(looked, abs=0.5)
    # Since the last look: the next change is the ping at 30.
    status, answer = wait(agent, run, {"until": "change", "timeout": 100, "since": looked})
    assert (answer["sim_time"], answer["why"]) == (30.0, "change")
    assert Event.objects.filter(run_id=run["id"], type="skip").count() == 2


def test_a_wait_to_a_moment_lands_on_it_though_the_clock_ran_on(api, agent):
    run = started(api, agent)
    status, answer = wait(agent, run, {"to": 12.25})
    assert (status, answer["sim_time"], answer["why"]) == (200, 12.25, "slept")
    assert [fired["at"] for fired in answer["fired"]] == [10.0]
    status, answer = wait(agent, run, {"until": "change", "to": 20.25})
    assert (answer["sim_time"], answer["why"]) == (20.25, "timeout")
    status, answer = wait(agent, run, {"until": "change", "to": 40.0})
    assert (answer["sim_time"], answer["why"]) == (30.0, "change")
    status, answer = wait(agent, run, {"to": 5.0})  # passed already: the clock stays
    assert answer["sim_time"] == answer["from"] >= 30.0


@pytest.mark.parametrize("mode", ["live", "virtual"])
def test_live_and_virtual_runs_refuse_with_409_naming_the_clock(api, agent, mode):
    run = started(api, agent, clock_mode=mode)
    status, answer = wait(agent, run, {"seconds": 10})
    assert status == 409
    assert f"clock is {mode}" in answer["detail"] and "fast_forward" in answer["detail"]


def test_a_wait_after_contact_is_refused(api, agent):
    run = started(api, agent)
    agent.post(run["contact_url"], {"message": "done"})
    status, answer = wait(agent, run, {"seconds": 10})
    assert status == 409 and "contacted" in answer["detail"]


def test_a_wait_never_passes_kill_at(api, agent):
    run = started(api, agent)
    status, answer = wait(agent, run, {"seconds": 100000})
    assert (status, answer["sim_time"], answer["why"]) == (200, 630.0, "kill_at")
    status, answer = wait(agent, run, {"until": "change"})  # past kill_at: nothing to skip
    assert answer["from"] == answer["sim_time"] >= 630.0 and answer["why"] == "kill_at"
    assert Event.objects.filter(run_id=run["id"], type="skip").count() == 1


@pytest.mark.parametrize(
    "body,named",
    [
        ({}, '{"seconds": s}'),
        ({"seconds": 1, "until": "change"}, '{"seconds": s}'),
        ({"seconds": -1}, "seconds: must be a finite number"),
        ({"seconds": "soon"}, "seconds: must be a finite number"),
        ({"seconds": True}, "seconds: must be a finite number"),
        ({"until": "lunch"}, 'until: must be "change"'),
        ({"until": "change", "timeout": -5}, "timeout: must be a finite number"),
        ({"seconds": 3, "timeout": 5}, "timeout goes with"),
        ({"seconds": 3, "since": 1}, "since goes with"),
        ({"seconds": 3, "to": 10}, '{"to": t}'),
        ({"until": "change", "timeout": 3, "to": 10}, '"timeout": s or "to": t'),
        ({"to": -2}, "to: must be a finite number"),
        ({"until": "change", "since": "then"}, "since: must be a finite number"),
        ({"seconds": 3, "sleep": 5}, "sleep: unknown field"),
        ([1, 2], '{"seconds": s}'),
    ],
)
def test_a_bad_body_is_a_400_naming_the_problem(api, agent, body, named):
    run = started(api, agent)
    status, answer = wait(agent, run, body)
    assert status == 400 and named in answer["detail"]
    assert not Event.objects.filter(run_id=run["id"], type="skip").exists()


def test_not_json_is_a_400(api, agent):
    run = started(api, agent)
    response = agent.post(run["wait_url"], "{oops", content_type="application/json")
    assert response.status_code == 400 and "not JSON" in response.json()["detail"]


def test_an_unknown_token_is_a_404(agent):
    assert agent.post("/r/nosuchtoken/wait", {"seconds": 1}).status_code == 404


def test_flat_init_accepts_the_clock_mode(api):
    body = {
        "environment": "tally",
        "event_timeline_end": 60,
        "events": [{"time": 0, "type": "preload", "payload": {"n": 1}}],
        "clock_mode": "fast_forward",
    }
    assert api.post("/init", body, format="json").status_code == 200
    run = api.get("/api/runs/?open=1").json()
    listed = run["results"] if isinstance(run, dict) else run
    assert listed[0]["clock_mode"] == "fast_forward"
    assert api.get("/close").status_code == 200  # the slot is free again
    body["clock_mode"] = "warp"
    response = api.post("/init", body, format="json")
    assert response.status_code == 422 and "clock_mode" in response.json()["detail"]
