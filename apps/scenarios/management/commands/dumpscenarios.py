"""`manage.py dumpscenarios [DIR]`: write every Scenario row back to DIR/<path>.

An unedited row reproduces the file it was loaded from byte for byte.
"""

from __future__ import annotations

from pathlib import Path

from django.conf import settings
from django.core.management.base import BaseCommand, CommandError

from apps.scenarios.models import Scenario
from apps.scenarios.serialization import scenario_text


class Command(BaseCommand):
    help = "Write the scenarios in the database to DIR/<env>/<file>.json (default SENTINEL_SCENARIO_DIR)."

    def add_arguments(self, parser):
        parser.add_argument(
            "directory", nargs="?", help="target folder (default: SENTINEL_SCENARIO_DIR)"
        )
        parser.add_argument("--environment", help="only this environment")

    def handle(self, *args, directory=None, environment=None, **options):
        root = Path(directory or settings.SENTINEL_SCENARIO_DIR).resolve()
        rows = Scenario.objects.prefetch_related("timeline")
        if environment:
            rows = rows.filter(environment=environment)
        count = 0
        for row in rows:
            target = (root / row.path).resolve()
            if not target.is_relative_to(root):
                raise CommandError(f"scenario {row.pk}: path {row.path!r} leaves the target folder")
            target.parent.mkdir(parents=True, exist_ok=True)
            with open(target, "w", encoding="utf-8", newline="") as fh:
                fh.write(scenario_text(row))
            count += 1
        self.stdout.write(f"wrote {count} scenario files to {root}")
