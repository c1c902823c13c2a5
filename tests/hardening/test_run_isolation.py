"""Runs are isolated from each other (finding 5): with SENTINEL_FLAT_ENDPOINTS off, no URL outside
a run's own touches that run — an agent holding another run's URLs cannot start or complete the
default slot's run through /redirect and /contact.
"""

from __future__ import annotations

import pytest
from django.test import Client
from rest_framework.test import APIClient

from apps.control.urls import flat_urlpatterns
from apps.scenarios.format import parse_scenario
from apps.tally.environment import tally_scenario
from events import lifecycle
from events.models import Event, Run, RunStatus

pytestmark = pytest.mark.django_db


def init_default_slot() -> Run:
    scenario = tally_scenario()
    body = {
        "environment": "tally",
        "event_timeline_end": scenario["event_timeline_end"],
        "eval_sql": scenario["eval_sql"],
        "condition_at": scenario["condition_at"],
        "events": scenario["events"],
    }
    assert APIClient().post("/init", body, format="json").status_code == 200
    return Run.objects.get(is_default_slot=True, closed_at__isnull=True)


def footprint(run: Run) -> tuple:
    run.refresh_from_db()
    return run.status, run.closed_at, Event.objects.filter(run_id=run.pk).count()


def test_with_flat_endpoints_on_an_agent_can_drive_the_default_slot():
    """The upstream protocol, kept by default: /redirect and /contact need no token."""
    slot = init_default_slot()
    agent = Client()
    assert agent.get("/redirect").status_code == 302
    assert agent.get("/contact").status_code == 200
    slot.refresh_from_db()
    assert slot.status == RunStatus.COMPLETED


def test_finding_5_with_flat_endpoints_off_no_other_url_touches_a_run(settings):
    slot = init_default_slot()  # made while the flat endpoints were on
    other = lifecycle.create_run(parse_scenario(tally_scenario(), source="t").to_run_spec())
    settings.SENTINEL_FLAT_ENDPOINTS = False
    before = footprint(slot), footprint(other)
    agent = Client()  # holds only `other`'s URLs
    for pattern in flat_urlpatterns:
        route = str(pattern.pattern).replace("<str:scenario_id>", "x")
        for method in (agent.get, agent.post):
            response = method(f"/{route}?time=5&environment=tally")
            assert response.status_code == 404, route
    assert (footprint(slot), footprint(other)) == before
    assert "SENTINEL_FLAT_ENDPOINTS=off" in agent.get("/redirect").json()["detail"]
    # The run's own URLs and the API still work.
    assert agent.get(f"/r/{other.token}/start").status_code == 302
    assert APIClient().post(f"/api/runs/{other.pk}/evaluate/").status_code == 200
