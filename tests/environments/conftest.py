"""Fixtures of the generic environment tests: starting a run of a scenario case."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest
from django.conf import settings

from apps.scenarios.format import Scenario
from events import lifecycle
from events.models import ClockMode, Run
from tests.environments.cases import Case, copy_upstream_catalog


@pytest.fixture(scope="session")
def upstream_catalog(tmp_path_factory) -> Callable[[str], Path]:
    """`upstream_catalog(env)`: a loadable copy of the original catalog for `env` (made once)."""
    made: dict[str, Path] = {}

    def catalog(environment: str) -> Path:
        if environment not in made:
            directory = tmp_path_factory.mktemp(f"upstream-catalog-{environment}")
            made[environment] = copy_upstream_catalog(environment, directory)
        return made[environment]

    return catalog


@pytest.fixture
def start(db, upstream_catalog) -> Callable[[Case], tuple[Scenario, Run]]:
    """`start(case)`: the case's scenario and a new run of it on a virtual clock at 0, its
    preload fired, over our catalog (or the original one for an upstream case)."""

    def start(case: Case) -> tuple[Scenario, Run]:
        scenario = case.load()
        catalog = (
            upstream_catalog(case.environment)
            if case.upstream
            else Path(settings.SENTINEL_CATALOG_DIR)
        )
        run = lifecycle.create_run(
            scenario.to_run_spec(), clock_mode=ClockMode.VIRTUAL, catalog_dir=catalog
        )
        return scenario, run

    return start
