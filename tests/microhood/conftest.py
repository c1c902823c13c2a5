"""Fixtures for MicroHood: runs of our scenarios on a virtual clock, and their URLs."""

from __future__ import annotations

from collections.abc import Callable

import pytest
from django.conf import settings
from django.test import Client

from apps.scenarios.format import parse_scenario
from events import lifecycle
from events.models import ClockMode, Run
from tests.microhood.timeline import OUR_SCENARIOS, scenario


@pytest.fixture
def hood_run(db) -> Callable[[str], Run]:
    """`hood_run("price-absolute-passive")`: a run of that scenario, preloaded, clock at 0."""

    def start(name: str) -> Run:
        spec = parse_scenario(scenario(OUR_SCENARIOS / f"{name}.json")).to_run_spec()
        return lifecycle.create_run(
            spec, clock_mode=ClockMode.VIRTUAL, catalog_dir=settings.SENTINEL_CATALOG_DIR
        )

    return start


@pytest.fixture
def browser() -> Client:
    return Client()


def url(run: Run, rest: str = "") -> str:
    return f"/r/{run.token}/microhood/{rest}"
