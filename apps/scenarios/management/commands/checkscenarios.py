"""`manage.py checkscenarios [DIR]`: which scenario files the library serves, and which not, why.

One line per problem (a file failing validation, a file repeating another's id), then a
summary, then whether each trigger shows (below), then how the targeted scenarios' condition times spread: a line per 100-second bin
(count and share) and a verdict. Exit 1 when a file fails validation or when one bin holds
more than 25 % of the targeted scenarios (the paper samples condition times uniformly in
[10, 600] s); a repeated id is reported but still runs by its path, as the original
benchmark's MicroFy pair does.

Then, for every targeted scenario, whether its trigger shows: the watched page (`watch_page`,
else the start page) rendered just before and at `condition_at` must read differently
(apps.scenarios.watching). A scenario where it does not is reported (`unseen: …`), not failed:
the original benchmark's files run unchanged, and ours are held to it by their own test.
"""

from __future__ import annotations

from django.core.management.base import BaseCommand, CommandError

from apps.scenarios.library import library, scenario_root
from apps.scenarios.spread import MAX_BIN_SHARE, MIN_JUDGED, Spread, condition_spread
from apps.scenarios.watching import unseen_triggers


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
        unseen = unseen_triggers(loaded.by_path.values())
        for check in unseen:
            self.stdout.write(f"unseen: {check.scenario}: {check.detail}")
        targeted = sum(1 for s in loaded.by_path.values() if s.condition_at is not None)
        self.stdout.write(
            f"watched pages: {targeted - len(unseen)} of {targeted} targeted scenarios "
            "change visibly at condition_at"
        )
        spread = condition_spread(loaded.by_path.values())
        self._print_spread(spread)
        if invalid:
            raise CommandError(f"{len(invalid)} scenario file(s) failed validation", returncode=1)
        if spread.crowded:
            raise CommandError("condition times are bunched (see the bins above)", returncode=1)

    def _print_spread(self, spread: Spread) -> None:
        self.stdout.write(f"condition_at of {spread.targeted} targeted scenarios:")
        for b in spread.bins:
            self.stdout.write(f"  {b.label}: {b.count:3d} ({100 * b.share:4.1f} %)")
        limit = f"{100 * MAX_BIN_SHARE:.0f} %"
        largest = max((b.share for b in spread.bins), default=0.0)
        if not spread.judged:
            verdict = f"not judged: fewer than {MIN_JUDGED} targeted scenarios"
        elif spread.crowded:
            names = ", ".join(f"{b.label} {100 * b.share:.1f} %" for b in spread.crowded)
            verdict = f"FAIL: above {limit} in {names}"
        else:
            verdict = f"ok: no bin above {limit} (largest {100 * largest:.1f} %)"
        self.stdout.write(f"condition_at spread: {verdict}")
