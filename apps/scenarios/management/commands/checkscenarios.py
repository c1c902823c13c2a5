"""`manage.py checkscenarios [DIR]`: which scenario files the library serves, and which not, why.

One line per problem (a file failing validation, a file repeating another's id), then a
summary. Exit 1 when a file fails validation; a repeated id is reported but still runs by its
path, as the original benchmark's MicroFy pair does.
"""

from __future__ import annotations

from django.core.management.base import BaseCommand, CommandError

from apps.scenarios.library import library, scenario_root


class Command(BaseCommand):
    help = "Check every scenario file (default SENTINEL_SCENARIO_DIR) and report the bad ones."

    def add_arguments(self, parser):
        parser.add_argument(
            "directory", nargs="?", help="scenario folder (default: SENTINEL_SCENARIO_DIR)"
        )

    def handle(self, *args, directory=None, **options):
        root = scenario_root(directory)
        try:
            loaded = library(root)
        except FileNotFoundError as error:
            raise CommandError(str(error)) from None
        invalid = [problem for problem in loaded.problems if not problem.duplicate_of]
        duplicates = [problem for problem in loaded.problems if problem.duplicate_of]
        for problem in loaded.problems:
            kind = "duplicate" if problem.duplicate_of else "invalid"
            self.stdout.write(f"{kind}: {problem.path}: {problem.detail}")
        self.stdout.write(
            f"{len(loaded.by_path)} scenario files load from {root} "
            f"({len(loaded.by_id)} ids); {len(invalid)} invalid, {len(duplicates)} repeat an id"
        )
        if invalid:
            raise CommandError(f"{len(invalid)} scenario file(s) failed validation", returncode=1)
