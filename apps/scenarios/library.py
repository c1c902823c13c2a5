"""The scenario library: every scenario file under SENTINEL_SCENARIO_DIR.

The files are the one source of truth in a running server: the API, the flat endpoints and
the harness read them here, and an admin edit is written through to its file (see
`apps.scenarios.sync`). The library is reloaded whenever a file's size or modification time
changes, so every reader sees an edit at its next request, in every server process.

One bad file never takes the library down: it is reported (`problems`) and the rest load.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass
from pathlib import Path

from django.conf import settings

from apps.scenarios.format import (
    DEV_FILENAME,
    LibraryProblem,
    LoadedLibrary,
    Scenario,
    load_dev_scenario,
    load_library,
)

_lock = threading.Lock()


@dataclass(frozen=True)
class _Cached:
    signature: tuple
    loaded: LoadedLibrary


_libraries: dict[Path, _Cached] = {}


class UnknownScenario(LookupError):
    def __init__(self, scenario_id: str):
        super().__init__(
            f"unknown scenario {scenario_id!r}; list them with GET /api/scenarios/ "
            "(an id, or a file's path such as micromail/x.json)"
        )


def scenario_root(root: Path | str | None = None) -> Path:
    return Path(root or settings.SENTINEL_SCENARIO_DIR).resolve()


def _signature(root: Path) -> tuple:
    """What changes when any scenario file is added, removed or rewritten."""
    entries = []
    for path in sorted(root.glob("*/*.json")):
        if path.name == DEV_FILENAME:
            continue
        try:
            stat = path.stat()
        except OSError:
            continue
        entries.append((path.name, path.parent.name, stat.st_mtime_ns, stat.st_size))
    return tuple(entries)


def library(root: Path | str | None = None) -> LoadedLibrary:
    """The folder's scenarios and problems, reloaded when a file changed on disk."""
    root = scenario_root(root)
    signature = _signature(root) if root.is_dir() else ()
    cached = _libraries.get(root)
    if cached is None or cached.signature != signature:
        with _lock:
            cached = _libraries.get(root)
            if cached is None or cached.signature != signature:
                cached = _libraries[root] = _Cached(signature, load_library(root))
    return cached.loaded


def scenario_library(root: Path | str | None = None) -> dict[str, Scenario]:
    """The scenarios by id (a repeated id belongs to the first file in path order)."""
    return library(root).by_id


def scenario_problems(root: Path | str | None = None) -> tuple[LibraryProblem, ...]:
    return library(root).problems


def is_path_reference(reference: str) -> bool:
    return "/" in reference or reference.endswith(".json")


def get_scenario(reference: str) -> Scenario:
    """A scenario by id, or by its file's path relative to the folder (`microfy/x.json`)."""
    loaded = library()
    found = (
        loaded.by_path.get(reference)
        if is_path_reference(reference)
        else loaded.by_id.get(reference)
    )
    if found is None:
        raise UnknownScenario(reference)
    return found


def get_dev_scenario(environment: str) -> Scenario:
    return load_dev_scenario(Path(settings.SENTINEL_SCENARIO_DIR), environment)
