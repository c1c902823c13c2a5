"""Benchmark fairness of the ticker: another run's lateness while one run fires a dense timeline.

Two live runs of the test-only `tally` environment on the in-process ticker (the configured
database): a dense one with `--entries` entries all due at once, and a quiet one with an entry
every 0.25 s over the same seconds. stdout gets one line:

    bench_dense: quiet_lateness_p99_ms=<f> quiet_lateness_max_ms=<f> dense_entries=<n> dense_fired_s=<f>

Target: quiet_lateness_max_ms ≤ 100 with 15,000 dense entries (the issue's figure).
"""

from __future__ import annotations

import threading
import time

from django.core.management.base import BaseCommand, CommandError

from events import lifecycle, registry
from events.models import Event, EventKind, Run
from events.ticker import run_ticker_in_thread
from sentinel_site.figures import percentile

DUE_AT = 2.0  # simulated = wall seconds (speed 1) after the start
QUIET_EVERY = 0.25
QUIET_SPAN = 6.0
PATIENCE_S = 300.0


class Command(BaseCommand):
    help = "Time another run's events while one run fires thousands of entries due at once."

    def add_arguments(self, parser):
        parser.add_argument("--entries", type=int, default=15_000)

    def handle(self, *args, entries: int, **options):
        if not 1 <= entries <= 20_000:
            raise CommandError(f"--entries must be 1–20000 (a timeline's bound), got {entries}")
        from apps.scenarios.format import parse_scenario
        from apps.tally.environment import TALLY, tally_scenario

        if TALLY.name not in registry.environment_names():
            registry.register(TALLY)

        def spec(name: str, times: list[float]) -> dict:
            data = tally_scenario(
                pings=[(0.0, 1)] + [(t, 1) for t in times], condition_at=None, eval_sql=None,
                scenario_id=name,
            )  # fmt: skip
            data["event_timeline_end"] = data["kill_at"] = DUE_AT + QUIET_SPAN + 1
            return parse_scenario(data, source="bench").to_run_spec()

        quiet_times = [DUE_AT + QUIET_EVERY * i for i in range(int(QUIET_SPAN / QUIET_EVERY))]
        dense = lifecycle.create_run(spec("bench-dense", [DUE_AT] * entries))
        quiet = lifecycle.create_run(spec("bench-quiet", quiet_times))
        stop = threading.Event()
        ticker = run_ticker_in_thread(stop)
        try:
            lifecycle.start_clock(dense)
            lifecycle.start_clock(quiet)
            deadline = time.monotonic() + PATIENCE_S
            while self._fired(quiet) < len(quiet_times) or self._fired(dense) < entries:
                if time.monotonic() > deadline:
                    raise CommandError("the ticker did not fire both timelines in time")
                time.sleep(0.2)
        finally:
            stop.set()
            ticker.join(timeout=10)
            for run in (dense, quiet):
                lifecycle.close(run)
        lateness = self._lateness(quiet)
        recorded = Event.objects.filter(run=dense, at__gt=0).values_list("recorded_at", flat=True)
        started = Run.objects.get(pk=dense.pk).started_at or 0.0
        self.stdout.write(
            f"bench_dense: quiet_lateness_p99_ms={percentile(lateness, 99):.2f} "
            f"quiet_lateness_max_ms={max(lateness):.2f} dense_entries={entries} "
            f"dense_fired_s={max(recorded) - started - DUE_AT:.2f}"
        )

    @staticmethod
    def _fired(run: Run) -> int:
        return Event.objects.filter(run=run, kind=EventKind.SCENARIO, at__gt=0).count()

    @staticmethod
    def _lateness(run: Run) -> list[float]:
        return list(
            Event.objects.filter(run=run, lateness_ms__isnull=False).values_list(
                "lateness_ms", flat=True
            )
        )
