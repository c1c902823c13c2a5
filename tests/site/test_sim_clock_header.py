"""Every page of a run reports the run's clock (apps.kit.sim_clock_header), and the reference
agent's reading of it (apps.browser_agent.sim_clock) lands on the run's own seconds, skips
included."""

from __future__ import annotations

import pytest
from django.test import Client
from rest_framework.test import APIClient

from apps.browser_agent.sim_clock import ClockReading, reading_from_headers, sim_time_now
from apps.tally.environment import tally_scenario

pytestmark = pytest.mark.django_db


def opened(clock_mode: str, speed_factor: float = 2.0) -> tuple[Client, dict, str]:
    """A tally run whose agent has opened its task URL; the start page's path."""
    run = (
        APIClient()
        .post(
            "/api/runs/",
            {
                "scenario_json": tally_scenario(),
                "clock_mode": clock_mode,
                "speed_factor": speed_factor,
            },
            format="json",
        )
        .json()
    )
    agent = Client()
    start = agent.get(run["task_url"])
    assert start.status_code == 302
    return agent, run, start["Location"]


def reading(response) -> ClockReading:
    headers = {name.lower(): value for name, value in response.headers.items()}
    found = reading_from_headers(headers, heard=0.0)
    assert found is not None, dict(response.headers)
    return found


def test_a_page_of_a_fast_forward_run_reports_the_skipped_clock_and_its_speed():
    agent, run, page = opened("fast_forward")
    answer = agent.post(run["wait_url"], {"seconds": 35}, content_type="application/json").json()
    seen = reading(agent.get(page, follow=True))
    # Read after the wait answered, on a clock running at speed 2 since.
    assert answer["sim_time"] <= seen.sim < answer["sim_time"] + 5
    assert seen.rate == 2.0


def test_a_virtual_clock_stands_still():
    agent, _, page = opened("virtual")
    seen = reading(agent.get(page, follow=True))
    assert (seen.sim, seen.rate) == (0.0, 0.0)


def test_a_page_of_no_run_reports_nothing():
    assert "X-Sentinel-Sim-Time" not in Client().get("/").headers


def test_the_latest_reading_is_carried_forward_by_its_rate():
    page = ClockReading(sim=40.0, rate=4.0, heard=100.0)
    wait = ClockReading(sim=300.0, rate=4.0, heard=90.0)  # heard before the page: older
    assert sim_time_now(lambda: page, lambda: wait, monotonic=lambda: 102.5) == 50.0
    assert sim_time_now(lambda: None, monotonic=lambda: 1.0) is None
