"""What the home page shows: the environments, the scenario library and the recent runs.

Generic over the registered environments (`events.registry`): no environment is imported.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass
from pathlib import Path

from django.conf import settings

from apps.bench.models import TaskResult
from apps.replay.models import RunVerdict
from apps.scenarios.format import DEV_FILENAME, LibraryProblem
from apps.scenarios.library import library, scenario_root
from events.models import Run
from events.registry import all_environments

RECENT_RUNS = 15

# The project's documents the home page links to (served read-only, as text).
DOCS = {
    "readme": ("README.md", "README: set up, run an agent, benchmark, configure"),
    "architecture": ("docs/architecture.md", "Architecture"),
    "adding-an-environment": ("docs/adding-an-environment.md", "Adding an environment"),
    "bench": ("apps/bench/README.md", "The benchmark harness"),
}


@dataclass(frozen=True)
class EnvironmentRow:
    name: str
    title: str
    scenarios: int
    has_dev: bool  # a dev.json: "browse with everything preloaded"


@dataclass(frozen=True)
class RunRow:
    run: Run
    verdict: str  # pass, fail, or what the run is doing when nobody graded it


def environment_rows() -> list[EnvironmentRow]:
    loaded = library()
    counts = Counter(scenario.environment for scenario in loaded.by_path.values())
    root = scenario_root()
    return [
        EnvironmentRow(
            name=environment.name,
            title=environment.title,
            scenarios=counts.get(environment.name, 0),
            has_dev=(root / environment.name / DEV_FILENAME).is_file(),
        )
        for environment in sorted(all_environments(), key=lambda e: e.name)
    ]


def scenario_problems() -> tuple[LibraryProblem, ...]:
    return library().problems


def scenario_count() -> int:
    return len(library().by_path)


def recent_runs(limit: int = RECENT_RUNS) -> list[RunRow]:
    """The newest runs, each with its harness result or recorded verdict when it has one."""
    runs = list(Run.objects.defer("scenario").order_by("-id")[:limit])
    ids = [run.pk for run in runs]
    graded = dict(
        TaskResult.objects.filter(run_id__in=ids, success__isnull=False).values_list(
            "run_id", "success"
        )
    )
    for run_id, success in (
        RunVerdict.objects.filter(run_id__in=ids).order_by("id").values_list("run_id", "success")
    ):
        graded.setdefault(run_id, success)
    rows = []
    for run in runs:
        if run.pk in graded:
            verdict = "pass" if graded[run.pk] else "fail"
        else:
            verdict = "closed, not graded" if run.closed_at else f"{run.status}, not graded"
        rows.append(RunRow(run, verdict))
    return rows


def doc_path(name: str) -> Path | None:
    entry = DOCS.get(name)
    return Path(settings.BASE_DIR) / entry[0] if entry else None
