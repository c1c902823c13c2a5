"""Fast-forward pacing on a real Daphne with one awake place (sentinel_site/pacing.py): a second
agent's first visit is held until the first agent waits, and the first agent's wait, held in
turn, lands where it would have; a live run is never held.

The cast: tally runs (pings at 0, 10, 30 and 50 s) at speed 1.
"""

from __future__ import annotations

import time
from concurrent.futures import ThreadPoolExecutor

import httpx
import pytest

from apps.tally.environment import tally_scenario
from events.clock import sim_now
from events.models import Run
from sentinel_site.pacing import AWAKE_LAPSE_S
from sentinel_site.site_server import site_server
from tests import control_api
from tests.server_urls import FORGET_PATH, PACING_PATH

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.slow]

CEILING_S = 30.0  # a ceiling, not a wait: each condition is met as soon as the server acts
HELD = "x-sentinel-held-ms"


@pytest.fixture(scope="module")
def paced_site(django_db_setup, django_db_blocker):
    places = {"SENTINEL_FAST_FORWARD_AWAKE": "1", "SENTINEL_TEST_SHARED_SERVER": "1"}
    with django_db_blocker.unblock(), site_server(extra_env=places) as base_url:
        yield base_url


@pytest.fixture(autouse=True)
def nobody_awake(paced_site):
    """Each test starts with every place free (an earlier test's runs would hold them)."""
    assert httpx.post(f"{paced_site}/{FORGET_PATH}", timeout=CEILING_S).status_code == 204


def new_run(base_url: str, clock_mode: str = "fast_forward") -> dict:
    body = {"scenario_json": tally_scenario(), "clock_mode": clock_mode}
    return control_api.post(base_url, "/api/runs/", body)


def held_tokens(base_url: str) -> list[str]:
    return httpx.get(f"{base_url}/{PACING_PATH}", timeout=CEILING_S).json()["held"]


def until(condition, what: str) -> None:
    deadline = time.monotonic() + CEILING_S
    while not condition():
        assert time.monotonic() < deadline, f"not within {CEILING_S} s: {what}"
        time.sleep(0.02)


def test_a_second_agent_starts_when_the_first_waits_whose_wait_lands_where_it_would_have(
    paced_site,
):
    first, second = new_run(paced_site), new_run(paced_site)
    with httpx.Client(timeout=CEILING_S) as agent, ThreadPoolExecutor(1) as other_agent:
        opened = agent.get(first["task_url"])
        assert opened.status_code == 302 and opened.headers[HELD] == "0"
        second_opens = other_agent.submit(agent.get, second["task_url"])
        until(lambda: second["token"] in held_tokens(paced_site), "the second visit is held")
        assert Run.objects.get(pk=second["id"]).status == "ready"  # its clock waits with it

        run = Run.objects.get(pk=first["id"])
        asked = sim_now(run, time.time())
        waited = agent.post(first["wait_url"], json={"seconds": 2})

        opened = second_opens.result(timeout=CEILING_S)
        assert opened.status_code == 302 and float(opened.headers[HELD]) > 0
        assert Run.objects.get(pk=second["id"]).status == "running_auto"
    # The first agent's wait was held while the second worked (it never waited), and let go
    # just before it would have ended: the clock ran meanwhile, the skip did the rest.
    assert waited.status_code == 200, waited.text
    answer = waited.json()
    assert float(waited.headers[HELD]) > 1000
    assert answer["sim_time"] == pytest.approx(asked + 2, abs=0.3)
    assert answer["sim_time"] - answer["from"] < 1.0


def test_a_live_runs_task_url_is_answered_while_every_place_is_taken(paced_site):
    awake, live = new_run(paced_site), new_run(paced_site, clock_mode="live")
    with httpx.Client(timeout=CEILING_S) as agent:
        assert agent.get(awake["task_url"]).status_code == 302
        opened = agent.get(live["task_url"])
    assert opened.status_code == 302 and HELD not in opened.headers
    assert held_tokens(paced_site) == []


def test_a_closed_runs_place_is_free_at_once(paced_site):
    # An agent that ends without contacting (a no-op task watched to its end) sends no last
    # wait: the harness's close of its run frees its place, not the 10-s lapse.
    ended, next_up = new_run(paced_site), new_run(paced_site)
    with httpx.Client(timeout=CEILING_S) as agent, ThreadPoolExecutor(1) as other_agent:
        assert agent.get(ended["task_url"]).status_code == 302
        next_opens = other_agent.submit(agent.get, next_up["task_url"])
        until(lambda: next_up["token"] in held_tokens(paced_site), "the next visit is held")
        control_api.post(paced_site, f"/api/runs/{ended['id']}/close/")
        opened = next_opens.result(timeout=CEILING_S)
    assert opened.status_code == 302
    # Held until the close, which came at once: far from the lapse's (and longest hold's) 10 s.
    assert float(opened.headers[HELD]) < AWAKE_LAPSE_S * 1000 / 2
