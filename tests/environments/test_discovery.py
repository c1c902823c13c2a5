"""What the generic tests play: every registered environment brings scenarios of its own, and
every requisite-action list for an original scenario names one that exists."""

from __future__ import annotations

import pytest

from events.registry import environment_names
from tests.environments.cases import (
    UPSTREAM,
    UPSTREAM_ABSENT,
    UPSTREAM_SOLUTIONS,
    our_cases,
    upstream_cases,
    upstream_solutions,
)


@pytest.mark.parametrize("environment", environment_names())
def test_every_environment_has_scenarios_of_ours_with_a_task_and_a_noop(environment):
    cases = our_cases(environment)
    assert any(not case.noop for case in cases), f"{environment}: no task scenario of ours"
    assert any(case.noop for case in cases), f"{environment}: no no-op scenario of ours"


@pytest.mark.upstream
@pytest.mark.parametrize("path", sorted(UPSTREAM_SOLUTIONS.glob("*.json")), ids=lambda p: p.stem)
def test_every_upstream_solution_names_an_original_scenario(path):
    if not UPSTREAM.is_dir():
        pytest.skip(UPSTREAM_ABSENT)
    environment = path.stem
    assert environment in environment_names(), f"{path.name}: no environment {environment!r}"
    known = {case.raw().get("id") for case in upstream_cases(environment)}
    unknown = sorted(set(upstream_solutions(environment)) - known)
    assert unknown == [], f"{path.name} names scenarios the original does not have: {unknown}"
