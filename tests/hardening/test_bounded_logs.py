"""What an agent sends cannot grow its own run's log without bound (finding: every GET logged its
full URL, ≈15 KB each)."""

from __future__ import annotations

import pytest
from django.test import Client

from apps.kit.links import environment_root
from apps.scenarios.library import get_scenario
from events import lifecycle
from events.commands import VIEW_PATH_LIMIT
from events.models import Event, EventKind

pytestmark = pytest.mark.django_db


def test_a_viewed_url_is_logged_up_to_the_limit_and_says_how_long_it_was():
    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    url = f"{environment_root(run)}/?q={'x' * 15_000}"
    assert Client().get(url).status_code == 200
    view = Event.objects.filter(run=run, kind=EventKind.VIEW).latest("seq")
    assert view.payload["path"] == url[:VIEW_PATH_LIMIT]
    assert view.payload["path_length"] == len(url)


def test_an_ordinary_url_is_logged_whole():
    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    url = f"{environment_root(run)}/?folder=inbox"
    assert Client().get(url).status_code == 200
    view = Event.objects.filter(run=run, kind=EventKind.VIEW).latest("seq")
    assert view.payload["path"] == url and "path_length" not in view.payload
