"""Shared fixtures: the `tally` test environment and a small named cast of runs."""

from __future__ import annotations

from pathlib import Path

import pytest

from apps.scenarios.format import parse_scenario
from events import registry
from events.projection import clear_cache
from tests.tally import TALLY, tally_scenario

REPO = Path(__file__).resolve().parents[1]
UPSTREAM = REPO.parent / "shared" / "upstream"


@pytest.fixture(scope="session", autouse=True)
def tally_environment():
    registry.register(TALLY)
    yield TALLY
    registry.unregister(TALLY.name)


@pytest.fixture(autouse=True)
def fresh_projection_cache():
    # Test databases reuse primary keys across tests; a cache keyed by run id must not leak.
    clear_cache()
    yield
    clear_cache()


@pytest.fixture
def tally_spec():
    def make(**kwargs) -> dict:
        return parse_scenario(tally_scenario(**kwargs), source="tests").to_run_spec()

    return make


@pytest.fixture
def upstream_dir() -> Path:
    if not UPSTREAM.is_dir():
        pytest.skip("../shared/upstream is absent")
    return UPSTREAM
