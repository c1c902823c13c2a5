"""`manage.py loadscenarios [DIR]`: import DIR/**/*.json into the Scenario tables.

The admin imports SENTINEL_SCENARIO_DIR by itself (apps.scenarios.sync) whenever it lists or
opens scenarios, so this command is only needed to check a whole folder in one go, or to load
rows from another folder (the admin then brings unedited rows back to SENTINEL_SCENARIO_DIR's
files).

Every file is validated before anything is written: one bad file means nothing changes, and
each problem is one line on stderr naming the file and the field.

Rows are keyed by path, so a load replaces the row at each file's path. A row whose text
differs from the file it would be replaced by — edited in the admin and not dumped yet, or
loaded from another folder with the same relative path — is not replaced unless `--replace`
says so: the load stops, naming those rows, before anything is written.
"""

from __future__ import annotations

from collections import defaultdict
from pathlib import Path

from django.conf import settings
from django.core.management.base import BaseCommand, CommandError

from apps.scenarios.format import ScenarioError
from apps.scenarios.models import Scenario
from apps.scenarios.serialization import (
    ScenarioFile,
    read_scenario_file,
    save_scenario_file,
    scenario_files,
    scenario_text,
)


class Command(BaseCommand):
    help = "Import scenario files (DIR/**/*.json, default SENTINEL_SCENARIO_DIR) into the admin."

    def add_arguments(self, parser):
        parser.add_argument(
            "directory", nargs="?", help="scenario folder (default: SENTINEL_SCENARIO_DIR)"
        )
        parser.add_argument(
            "--replace",
            action="store_true",
            help="replace rows that differ from their files (admin edits not yet dumped are lost)",
        )

    def handle(self, *args, directory=None, replace=False, **options):
        root = Path(directory or settings.SENTINEL_SCENARIO_DIR).resolve()
        if not root.is_dir():
            raise CommandError(f"scenario folder not found: {root}")
        read, errors = [], []
        for path in scenario_files(root):
            try:
                read.append(read_scenario_file(path, root))
            except ScenarioError as error:
                errors.append(str(error))
        if errors:
            for line in errors[:-1]:
                self.stderr.write(line)
            raise CommandError(
                f"{errors[-1]}"
                + (
                    f" ({len(errors)} files invalid; nothing imported)"
                    if len(errors) > 1
                    else " (nothing imported)"
                )
            )
        new, unchanged, differing = _compare_with_rows(read)
        if differing and not replace:
            for path in differing[:-1]:
                self.stderr.write(f"{path}: the row differs from {root / path}")
            raise CommandError(
                f"{differing[-1]}: the row differs from {root / differing[-1]} "
                f"({len(differing)} rows differ: edited in the admin, or loaded from another "
                "folder; nothing imported). Keep the rows with `manage.py dumpscenarios DIR` "
                "first, or pass --replace to overwrite them."
            )
        by_id = defaultdict(list)
        for scenario_file in read:
            save_scenario_file(scenario_file)
            by_id[scenario_file.row.scenario_id].append(scenario_file.row.path)
        for scenario_id, paths in sorted(by_id.items()):
            if len(paths) > 1:
                self.stderr.write(f"note: id {scenario_id!r} is shared by {', '.join(paths)}")
        self.stdout.write(
            f"imported {len(read)} scenario files from {root} ({len(new)} new, "
            f"{len(differing)} replaced, {len(unchanged)} unchanged)"
        )


def _compare_with_rows(read: list[ScenarioFile]) -> tuple[list[str], list[str], list[str]]:
    """The files' paths split into: no row yet, row identical to the file, row that differs."""
    rows = Scenario.objects.prefetch_related("timeline").in_bulk(
        [scenario_file.row.path for scenario_file in read], field_name="path"
    )
    new, unchanged, differing = [], [], []
    for scenario_file in read:
        path = scenario_file.row.path
        row = rows.get(path)
        if row is None:
            new.append(path)
            continue
        (unchanged if scenario_text(row) == scenario_file.text else differing).append(path)
    return new, unchanged, differing
