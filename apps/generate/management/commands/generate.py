"""`manage.py generate --seed S --count N --out DIR [--env E …] [--families F …]`: new scenarios
composed from the hand-written ones, each proven before it is written (apps.generate).

Prints progress per environment, the discards by reason, the diversity figures and the wall
time; exit 2 on bad input (the message names it).
"""

from __future__ import annotations

import time
from pathlib import Path

from django.conf import settings
from django.core.management.base import BaseCommand, CommandError

from apps.generate.compose import ASPECTS
from apps.generate.figures import diversity
from apps.generate.generate import GenerationError, generate
from apps.scenarios.library import scenario_root


class Command(BaseCommand):
    help = "Generate proven scenarios from the hand-written ones into a folder of their own."

    def add_arguments(self, parser):
        parser.add_argument("--seed", type=int, required=True)
        parser.add_argument("--count", type=int, required=True, help="scenarios to write")
        parser.add_argument("--out", required=True, help="output folder (new, empty or generated)")
        parser.add_argument(
            "--env", action="append", dest="environments", help="only this environment (repeat)"
        )
        parser.add_argument(
            "--families",
            nargs="+",
            help="only these families (file names of the templates, <family>-withheld) or "
            "kinds (passive, active, noop)",
        )
        parser.add_argument(
            "--vary",
            nargs="+",
            default=list(ASPECTS),
            choices=ASPECTS,
            help="what varies from the template (default: all)",
        )
        parser.add_argument(
            "--templates", help="hand-written scenario folder (default: SENTINEL_SCENARIO_DIR)"
        )

    def handle(self, *args, seed, count, out, environments, families, vary, templates, **_):
        began = time.monotonic()
        root = scenario_root(templates)
        try:
            result = generate(
                seed=seed,
                count=count,
                out=Path(out),
                templates_root=root,
                environments=environments,
                families=families,
                aspects=tuple(a for a in ASPECTS if a in vary),
                protected=(root, Path(settings.SENTINEL_CATALOG_DIR)),
                progress=self.stdout.write,
            )
        except GenerationError as error:
            raise CommandError(str(error), returncode=2) from None
        discarded = sum(result.discarded.values())
        self.stdout.write(
            f"candidates: {result.candidates}; discarded: {discarded} failing a proof, "
            f"{result.duplicates} duplicates"
        )
        for reason, n in result.discarded.most_common():
            self.stdout.write(f"  {n:5d}  {reason}")
        for family, reason in sorted(result.unprovable.items()):
            self.stdout.write(
                f"not generated from (its template fails a proof): {family}: {reason}"
            )
        for family in result.abandoned:
            self.stdout.write(f"abandoned (no proven candidate in a row of tries): {family}")
        for line in diversity(result.entries, result.documents):
            self.stdout.write(line)
        self.stdout.write(
            f"generate: seed={seed} written={len(result.entries)} candidates={result.candidates} "
            f"discarded={discarded} duplicates={result.duplicates} "
            f"wall_s={time.monotonic() - began:.1f} out={out}"
        )
