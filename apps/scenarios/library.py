"""The scenario library: every scenario file under SENTINEL_SCENARIO_DIR, loaded once."""

from __future__ import annotations

import threading
from pathlib import Path

from django.conf import settings

from apps.scenarios.format import Scenario, load_dev_scenario, load_scenarios

_lock = threading.Lock()
_libraries: dict[Path, dict[str, Scenario]] = {}


class UnknownScenario(LookupError):
    def __init__(self, scenario_id: str):
        super().__init__(f"unknown scenario {scenario_id!r}; list them with GET /scenarios")


def scenario_library(root: Path | None = None) -> dict[str, Scenario]:
    root = Path(root or settings.SENTINEL_SCENARIO_DIR).resolve()
    library = _libraries.get(root)
    if library is None:
        with _lock:
            library = _libraries.get(root)
            if library is None:
                library = _libraries[root] = load_scenarios(root)
    return library


def get_scenario(scenario_id: str) -> Scenario:
    try:
        return scenario_library()[scenario_id]
    except KeyError:
        raise UnknownScenario(scenario_id) from None


def get_dev_scenario(environment: str) -> Scenario:
    return load_dev_scenario(Path(settings.SENTINEL_SCENARIO_DIR), environment)
