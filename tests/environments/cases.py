"""Which scenarios the generic tests play: every registered environment's, found by folder.

- Ours, with their `solution` steps: the repository's `scenarios/<env>/*.json` (the benchmark's)
  and `tests/environments/scenarios/<env>/*.json` (test-only ones), over our catalog.
- The original SentinelBench's: `../shared/upstream/scenarios/<env>/*.json`, over the original
  catalog (marker `upstream`; skipped when ../shared/upstream is absent). Their files carry no
  `solution`: the requisite actions come from `upstream_solutions/<env>.json`,
  `{scenario_id: [{action, payload}, …]}` (MicroMail's: the two tasks whose eval_sql needs the
  message read, i.e. opened in the client; the original's own tests list none).

A new environment gets every generic test by registering and adding scenario files. Files are
only read as raw JSON here (to sort them into kinds); a scenario that does not validate fails
its own tests when they load it, instead of breaking the collection.
"""

from __future__ import annotations

import functools
import json
import os
import shutil
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest

from apps.scenarios.format import (
    DEV_FILENAME,
    SENTINELBENCH_ENVIRONMENTS,
    Scenario,
    parse_scenario,
    read_json_file,
)
from events.registry import environment_names
from tests.conftest import OUR_SCENARIOS

HERE = Path(__file__).resolve().parent
TEST_SCENARIOS = HERE / "scenarios"
UPSTREAM_SOLUTIONS = HERE / "upstream_solutions"
UPSTREAM = Path(  # beside the repository, or SENTINEL_UPSTREAM_DIR (README, Conformance tests)
    os.environ.get("SENTINEL_UPSTREAM_DIR") or HERE.parents[2] / "shared" / "upstream"
)
UPSTREAM_SCENARIOS = UPSTREAM / "scenarios"
UPSTREAM_CATALOGS = UPSTREAM / "catalogs"
UPSTREAM_ABSENT = (
    f"original SentinelBench data absent: no {UPSTREAM} (set SENTINEL_UPSTREAM_DIR; "
    "README, Conformance tests)"
)


UPSTREAM_DEFECTS = (
    HERE / "upstream_defects.json"
)  # original files that cannot be checked as they are


@functools.cache
def upstream_defects() -> dict[str, dict[str, dict[str, str]]]:
    """environment → file stem → {"condition_at" | "unreachable": why} (see the file's _about)."""
    return json.loads(UPSTREAM_DEFECTS.read_text(encoding="utf-8"))


def upstream_solutions(environment: str) -> dict[str, list[dict[str, Any]]]:
    """Our requisite actions for the original scenarios of `environment` ({} when none)."""
    path = UPSTREAM_SOLUTIONS / f"{environment}.json"
    return json.loads(path.read_text(encoding="utf-8")) if path.is_file() else {}


@dataclass(frozen=True)
class Case:
    """One scenario file of one environment, sorted into kinds from its raw JSON."""

    environment: str
    path: Path
    upstream: bool = False

    @property
    def id(self) -> str:
        return f"{self.environment}/{'upstream/' if self.upstream else ''}{self.path.stem}"

    def raw(self) -> dict[str, Any]:
        try:
            data = json.loads(self.path.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return {}
        return data if isinstance(data, dict) else {}

    def solution(self) -> list:
        data = self.raw()
        if self.upstream:
            return upstream_solutions(self.environment).get(data.get("id"), [])
        return data.get("solution") or []

    def defect(self, kind: str) -> str | None:
        """Why this original file cannot be checked for `kind` ("condition_at": its timing;
        "unreachable": its condition at all) — None when it can (all of ours can)."""
        if not self.upstream:
            return None
        known = upstream_defects().get(self.environment, {}).get(self.path.stem, {})
        return known.get(kind) or (known.get("unreachable") if kind == "condition_at" else None)

    @property
    def noop(self) -> bool:
        data = self.raw()
        return "condition_at" in data and data["condition_at"] is None

    @property
    def needs_action(self) -> bool:
        """An active task with a solution: its eval_sql needs the agent to act, not only see."""
        taxonomy = self.raw().get("taxonomy") or {}
        return taxonomy.get("monitoring_approach") == "active" and bool(self.solution())

    def load(self) -> Scenario:
        """The validated scenario (an upstream one with our solution for it)."""
        _, data = read_json_file(self.path)
        if self.upstream and isinstance(data, dict):
            data = {
                **data,
                "solution": upstream_solutions(self.environment).get(data.get("id"), []),
            }
        return parse_scenario(data, source=str(self.path))


def scenario_files(folder: Path) -> list[Path]:
    if not folder.is_dir():
        return []
    return sorted(p for p in folder.glob("*.json") if p.name != DEV_FILENAME)


def our_cases(environment: str) -> list[Case]:
    # The session's copy of the tracked files, not SENTINEL_SCENARIO_DIR: tests that edit
    # scenarios (the admin writes edits through to files) work on copies of their own, and these
    # cases must stay as authored whatever ran before them.
    folders = (OUR_SCENARIOS / environment, TEST_SCENARIOS / environment)
    return [Case(environment, path) for folder in folders for path in scenario_files(folder)]


def upstream_cases(environment: str) -> list[Case]:
    return [
        Case(environment, path, upstream=True)
        for path in scenario_files(UPSTREAM_SCENARIOS / environment)
    ]


def all_cases(*, upstream: bool = True) -> Iterator[Case]:
    for environment in environment_names():
        yield from our_cases(environment)
        if upstream:
            yield from upstream_cases(environment)


def params(*, noop: bool | None = None, needs_action: bool = False, upstream: bool = True):
    """pytest params over every environment's cases of a kind; the original's are marked
    `upstream`, and stand in as one skipped param per SentinelBench environment when
    ../shared/upstream is absent."""
    chosen = [
        pytest.param(case, id=case.id, marks=[pytest.mark.upstream] if case.upstream else [])
        for case in all_cases(upstream=upstream)
        if (noop is None or case.noop == noop) and (case.needs_action or not needs_action)
    ]
    if upstream and not UPSTREAM.is_dir():
        chosen += [
            pytest.param(
                None,
                id=f"{environment}/upstream",
                marks=[pytest.mark.upstream, pytest.mark.skip(reason=UPSTREAM_ABSENT)],
            )
            for environment in environment_names()
            if environment in SENTINELBENCH_ENVIRONMENTS
        ]
    return chosen


def copy_upstream_catalog(environment: str, directory: Path) -> Path:
    """The original catalog's shared files and `environment`'s folder, copied to `directory`.

    Not the whole catalog: the core loader rejects it, because another environment's table
    (microgram/suggestions.jsonl) has records without an `id`.
    """
    if not UPSTREAM_CATALOGS.is_dir():
        pytest.skip(UPSTREAM_ABSENT)
    for name in ("users.json", "entities.json"):
        shutil.copyfile(UPSTREAM_CATALOGS / name, directory / name)
    if (UPSTREAM_CATALOGS / environment).is_dir():
        shutil.copytree(UPSTREAM_CATALOGS / environment, directory / environment)
    return directory
