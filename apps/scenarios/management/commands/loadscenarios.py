"""`manage.py loadscenarios [DIR]`: import DIR/**/*.json into the Scenario tables.

Every file is validated before anything is written: one bad file means nothing changes, and
each problem is one line on stderr naming the file and the field.
"""

from __future__ import annotations

from collections import defaultdict
from pathlib import Path

from django.conf import settings
from django.core.management.base import BaseCommand, CommandError

from apps.scenarios.format import ScenarioError
from apps.scenarios.serialization import read_scenario_file, save_scenario_file, scenario_files


class Command(BaseCommand):
    help = "Import scenario files (DIR/**/*.json, default SENTINEL_SCENARIO_DIR) into the admin."

    def add_arguments(self, parser):
        parser.add_argument(
            "directory", nargs="?", help="scenario folder (default: SENTINEL_SCENARIO_DIR)"
        )

    def handle(self, *args, directory=None, **options):
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
        by_id = defaultdict(list)
        for scenario_file in read:
            save_scenario_file(scenario_file)
            by_id[scenario_file.row.scenario_id].append(scenario_file.row.path)
        for scenario_id, paths in sorted(by_id.items()):
            if len(paths) > 1:
                self.stderr.write(f"note: id {scenario_id!r} is shared by {', '.join(paths)}")
        self.stdout.write(f"imported {len(read)} scenario files from {root}")
