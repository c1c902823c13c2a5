"""Scenario rows and scenario files kept in step: the files are the one source of truth.

- `sync_from_files` imports the folder into the rows (the admin calls it whenever it lists or
  shows scenarios, so no manual `loadscenarios` is needed): a new file becomes a row, a file
  changed on disk replaces a row nobody edited, and a file that fails validation is reported.
- `write_through` writes an admin edit to its file, so the API, the flat endpoints and the
  harness (which read the files, `apps.scenarios.library`) run exactly what the admin shows.
- `file_conflict` is checked before an admin edit is saved: a file changed on disk since its
  row was read is reported, and neither side is overwritten.

Each row keeps the sha256 of its file's text as of the moment they last agreed
(`Scenario.file_sha256`): that tells "the file changed" from "the row changed".
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

from apps.scenarios.format import ScenarioError
from apps.scenarios.library import scenario_root
from apps.scenarios.models import Scenario
from apps.scenarios.serialization import (
    read_scenario_file,
    save_scenario_file,
    scenario_files,
    scenario_text,
    sha256,
)


class ScenarioFileError(ValueError):
    """A row cannot be written to its file; the message is one line for the author."""


@dataclass
class SyncReport:
    imported: list[str] = field(default_factory=list)  # new files, now rows
    replaced: list[str] = field(default_factory=list)  # changed on disk, row was unedited
    removed: list[str] = field(default_factory=list)  # deleted on disk, row was unedited
    problems: list[str] = field(default_factory=list)  # one line each: path and reason


def _file_path(row_path: str, root: Path) -> Path:
    return (root / row_path).resolve()


def _row_is_unedited(row: Scenario) -> bool:
    return bool(row.file_sha256) and sha256(scenario_text(row)) == row.file_sha256


def sync_from_files(root: Path | str | None = None) -> SyncReport:
    """Bring the rows in line with the scenario folder (see the module doc)."""
    root = scenario_root(root)
    report = SyncReport()
    if not root.is_dir():
        report.problems.append(f"scenario folder not found: {root}")
        return report
    rows = {row.path: row for row in Scenario.objects.prefetch_related("timeline")}
    seen = set()
    for path in scenario_files(root):
        relative = path.relative_to(root).as_posix()
        seen.add(relative)
        try:
            text = path.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError) as error:
            report.problems.append(f"{relative}: cannot read: {error}")
            continue
        row = rows.get(relative)
        if row is not None and row.file_sha256 == sha256(text):
            continue  # nothing changed on disk since row and file last agreed
        if row is not None and scenario_text(row) == text:
            Scenario.objects.filter(pk=row.pk).update(file_sha256=sha256(text))
            continue
        if row is not None and not _row_is_unedited(row):
            report.problems.append(
                f"{relative}: the file differs from its row, which was edited in the admin "
                "(or loaded from elsewhere); neither was overwritten. Keep the file with "
                "`manage.py loadscenarios --replace`, or the row with `manage.py dumpscenarios`"
            )
            continue
        try:
            scenario_file = read_scenario_file(path, root)
        except ScenarioError as error:
            report.problems.append(f"{relative}: {error}")
            continue
        save_scenario_file(scenario_file)
        (report.replaced if row is not None else report.imported).append(relative)
    for relative, row in rows.items():
        if relative in seen:
            continue
        if _row_is_unedited(row):
            row.delete()
            report.removed.append(relative)
        elif row.file_sha256:
            report.problems.append(
                f"{relative}: the file was deleted on disk but its row was edited in the admin; "
                "save the row again to write the file, or delete the row"
            )
    return report


def file_conflict(row: Scenario, root: Path | str | None = None) -> str | None:
    """Why saving `row` now would overwrite a change made on disk, or None.

    `row` is the row as it was read from the database (before the author's edit)."""
    root = scenario_root(root)
    path = _file_path(row.path, root)
    exists = path.is_file()
    if row.pk is None:
        return f"a file already exists at {row.path}; choose another path" if exists else None
    if not row.file_sha256 or not exists:
        return None
    try:
        on_disk = sha256(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError):
        return None
    if on_disk != row.file_sha256:
        return (
            f"{row.path} changed on disk since this scenario was opened; your edit was not "
            "saved and the file was not overwritten. Reopen the scenario to see the file's "
            "version, then edit again"
        )
    return None


def path_problem(relative: str, environment: str, root: Path | str | None = None) -> str | None:
    """A row's path must be `<environment>/<name>.json` inside the scenario folder."""
    root = scenario_root(root)
    parts = relative.split("/")
    if len(parts) != 2 or not parts[1].endswith(".json") or parts[1] == ".json":
        return f"must be <environment>/<name>.json, e.g. {environment or 'micromail'}/my-task.json"
    if environment and parts[0] != environment:
        return f"must be in the environment's folder: {environment}/{parts[1]}"
    if not _file_path(relative, root).is_relative_to(root):
        return "must stay inside the scenario folder"
    target = _file_path(relative, root)
    folder = target.parent if target.parent.is_dir() else root
    if not os.access(folder, os.W_OK) or (target.exists() and not os.access(target, os.W_OK)):
        return f"cannot be written: {target} is read-only (an edit must go to its file)"
    return None


def write_through(row: Scenario, root: Path | str | None = None) -> str:
    """Write `row` to its file (atomically) and record that they agree; the text written."""
    root = scenario_root(root)
    target = _file_path(row.path, root)
    if not target.is_relative_to(root):
        raise ScenarioFileError(f"{row.path}: leaves the scenario folder {root}")
    text = scenario_text(row)
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        temporary = target.with_name(f".{target.name}.tmp")
        with open(temporary, "w", encoding="utf-8", newline="") as fh:
            fh.write(text)
        temporary.replace(target)
    except OSError as error:
        raise ScenarioFileError(f"{row.path}: cannot write {target}: {error}") from None
    Scenario.objects.filter(pk=row.pk).update(file_sha256=sha256(text))
    row.file_sha256 = sha256(text)
    return text


def delete_file(row: Scenario, root: Path | str | None = None) -> None:
    """Remove a deleted row's file, so the next import does not bring the row back."""
    target = _file_path(row.path, scenario_root(root))
    if target.is_relative_to(scenario_root(root)):
        target.unlink(missing_ok=True)
