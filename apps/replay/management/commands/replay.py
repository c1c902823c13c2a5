"""`manage.py replay RUN`: refold the log from scratch, regrade, compare with the record.

Exit status 0 when the verdict, the log and the final state match what was recorded, 1 otherwise.
Grading uses events.evaluation.grade, which is read-only: replaying never completes a run.
"""

import json

from django.core.management.base import BaseCommand, CommandError

from apps.replay.management.commands._runs import get_run
from apps.replay.records import record_verdict, replay


class Command(BaseCommand):
    help = "Refold a run from scratch and check its verdict and final state against the record."

    def add_arguments(self, parser):
        parser.add_argument("run", help="run id or token")
        parser.add_argument("--json", action="store_true", help="print the full report as JSON")
        parser.add_argument(
            "--record",
            action="store_true",
            help="record the current verdict and digests as the reference first (then it matches)",
        )

    def handle(self, *args, run, json: bool = False, record: bool = False, **options):
        run = get_run(run)
        if record:
            record_verdict(run, source="replay --record")
        report = replay(run)
        if json:
            self.stdout.write(_dumps(report))
        verdict = report.replayed
        self.stdout.write(
            f"run {report.run}: replayed verdict {'PASS' if verdict['success'] else 'FAIL'} "
            f"({verdict['detail']}); {verdict['event_count']} events; state {verdict['state_digest'][:12]}"
        )
        if report.matches:
            self.stdout.write("match: verdict, log and final state are as recorded")
            return
        if report.recorded is None:
            raise CommandError(
                f"not graded yet: run {report.run} has no recorded verdict to compare with "
                "(pass --record to record one now, or export the run)"
            )
        raise CommandError("mismatch: " + "; ".join(report.differences))


def _dumps(report) -> str:
    return json.dumps(
        {
            "run": report.run,
            "matches": report.matches,
            "recorded": report.recorded,
            "replayed": report.replayed,
            "differences": report.differences,
        },
        indent=2,
    )
