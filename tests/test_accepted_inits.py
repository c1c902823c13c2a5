"""An `/init` body accepted once is not parsed and checked again (issue #29), and that changes
nothing a caller sees: the same run is made, another body is checked for itself, a refused
body is refused every time."""

from __future__ import annotations

import pytest
from rest_framework.test import APIClient

from apps.control import accepted_inits
from apps.control.serializers import InitPayloadSerializer
from events.models import Run
from tests.test_flat_protocol import init_body

pytestmark = pytest.mark.django_db


@pytest.fixture
def api():
    accepted_inits._kept.clear()
    return APIClient()


def reset(api, body: dict):
    api.get("/close")
    return api.post("/init", body, format="json")


def test_the_same_body_makes_the_same_run_without_being_checked_again(api, monkeypatch):
    assert reset(api, init_body()).status_code == 200
    first = Run.objects.get(is_default_slot=True, closed_at__isnull=True)

    def checked_again(*args, **kwargs):
        raise AssertionError("an accepted body was validated again")

    monkeypatch.setattr(InitPayloadSerializer, "is_valid", checked_again)
    assert reset(api, init_body()).json()["status"] == "ready"
    second = Run.objects.get(is_default_slot=True, closed_at__isnull=True)
    assert second.pk != first.pk
    assert second.scenario == first.scenario


def test_another_body_is_checked_for_itself(api):
    assert reset(api, init_body()).status_code == 200
    changed = reset(api, init_body(pings=[(0.0, 4), (10.0, 1)]))
    assert changed.status_code == 200
    run = Run.objects.get(is_default_slot=True, closed_at__isnull=True)
    assert run.spec["events"][0]["payload"] == {"n": 4}


def test_a_refused_body_is_refused_every_time(api):
    for _ in range(2):
        response = reset(api, init_body(speed_factor=0))
        assert response.status_code == 422
        assert "speed_factor" in response.json()["detail"]
    assert len(accepted_inits._kept._entries) == 0
