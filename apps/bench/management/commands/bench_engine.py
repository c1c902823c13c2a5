"""Benchmark the engine: lateness of fired events, append and fold throughput, reset time.

Drives N concurrent live runs with busy timelines through the in-process ticker on whatever
database is configured (embedded SQLite by default), while agent threads read state and act.
It uses the test-only `tally` environment so it measures the engine, not an environment's
reducers. Prints exactly one summary line at the end.
"""

from __future__ import annotations

import random
import statistics
import threading
import time

from django.core.management.base import BaseCommand, CommandError
from django.db import close_old_connections
from django.test import Client

from events import lifecycle, registry
from events.commands import current_state, perform_action
from events.models import Event, EventKind, Run
from events.projection import fold_from_scratch
from events.store import append_event
from events.ticker import run_ticker_in_thread
from events.timing import SpeedFactorError, validate_speed_factor
from sentinel_site.figures import percentile


class Command(BaseCommand):
    help = "Benchmark lateness, append/fold throughput and reset time of the run engine."

    def add_arguments(self, parser):
        parser.add_argument("--runs", type=int, default=100)
        parser.add_argument("--seconds", type=float, default=60.0, help="wall seconds of live play")
        parser.add_argument("--speed", type=float, default=4.0, help="speed factor of every run")
        parser.add_argument(
            "--agents", type=int, default=4, help="agent threads reading and acting"
        )

    def handle(self, *args, runs: int, seconds: float, speed: float, agents: int, **options):
        try:
            validate_speed_factor(speed)
        except SpeedFactorError as exc:
            raise CommandError(str(exc)) from None
        if runs < 1 or seconds <= 0:
            raise CommandError("--runs must be ≥ 1 and --seconds > 0")
        from apps.tally.environment import TALLY, tally_scenario

        if TALLY.name not in registry.environment_names():
            registry.register(TALLY)
        from apps.scenarios.format import parse_scenario

        rng = random.Random(42)
        authored_span = seconds * speed
        specs = []
        for index in range(runs):
            # ~2 events per wall second per run, at irregular times, on top of a t=0 preload.
            count = int(seconds * 2)
            times = sorted(round(rng.uniform(0.5, authored_span), 3) for _ in range(count))
            data = tally_scenario(
                pings=[(0.0, 1)] + [(t, 1) for t in times],
                condition_at=None,
                eval_sql=None,
                scenario_id=f"bench-{index}",
            )
            data["event_timeline_end"] = data["kill_at"] = max(authored_span + 1, 1.0)
            specs.append(parse_scenario(data, source="bench").to_run_spec())

        created = [lifecycle.create_run(spec, speed_factor=speed) for spec in specs]
        stop = threading.Event()
        ticker_thread = run_ticker_in_thread(stop)
        for run in created:
            lifecycle.start_clock(run)
            time.sleep(0.2 / runs)  # stagger starts a little, as real agents would

        appended = [0]

        def agent(seed: int) -> None:
            local = random.Random(seed)
            try:
                while not stop.is_set():
                    run = local.choice(created)
                    current_state(run)
                    perform_action(run, "poke", {"n": 1})
                    appended[0] += 1
                    time.sleep(0.1)
            finally:
                close_old_connections()

        agent_threads = [
            threading.Thread(target=agent, args=(i,), daemon=True) for i in range(agents)
        ]
        for thread in agent_threads:
            thread.start()
        time.sleep(seconds + 0.5)
        stop.set()
        for thread in agent_threads:
            thread.join()
        ticker_thread.join(timeout=10)

        run_ids = [run.pk for run in created]
        lateness = list(
            Event.objects.filter(
                run_id__in=run_ids, kind=EventKind.SCENARIO, lateness_ms__isnull=False
            ).values_list("lateness_ms", flat=True)
        )
        expected = sum(len([e for e in s["events"] if e["time"] > 0]) for s in specs)
        self.stderr.write(f"fired {len(lateness)} of {expected} timed entries across {runs} runs")

        append_rate = self._append_rate(created[0])
        fold_rate = self._fold_rate(created[0])
        reset_ms = self._reset_ms(specs[0])
        for run in created:
            lifecycle.close(run)
        self.stdout.write(
            "bench_engine: "
            f"lateness_p50_ms={percentile(lateness, 50):.2f} "
            f"lateness_p99_ms={percentile(lateness, 99):.2f} "
            f"lateness_max_ms={max(lateness) if lateness else float('nan'):.2f} "
            f"append_events_per_s={append_rate:.0f} "
            f"fold_events_per_s={fold_rate:.0f} "
            f"reset_ms_median={reset_ms:.2f}"
        )

    def _append_rate(self, run: Run, seconds: float = 3.0, writers: int = 2) -> float:
        counts = [0] * writers

        def writer(index: int) -> None:
            deadline = time.monotonic() + seconds
            try:
                while time.monotonic() < deadline:
                    append_event(run, EventKind.ACTION, "poke", {"n": 1}, at=0.0)
                    counts[index] += 1
            finally:
                close_old_connections()

        threads = [threading.Thread(target=writer, args=(i,)) for i in range(writers)]
        started = time.monotonic()
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        return sum(counts) / (time.monotonic() - started)

    def _fold_rate(self, run: Run, events: int = 4000) -> float:
        # A fixed prefix of the log: the tally state grows with every poke, so folding however
        # many events the append phase happened to write would measure the tally, not the fold.
        upto = min(events, Event.objects.filter(run=run).count())
        fold_from_scratch(run, upto)  # warm the catalog and the query path
        best = 0.0
        for _ in range(3):
            started = time.perf_counter()
            last_seq = fold_from_scratch(run, upto).seq
            best = max(best, last_seq / (time.perf_counter() - started))
        return best

    def _reset_ms(self, spec: dict, rounds: int = 21) -> float:
        client = Client(HTTP_HOST="127.0.0.1")  # a name ALLOWED_HOSTS admits by default
        body = {
            k: spec[k]
            for k in (
                "environment",
                "event_timeline_end",
                "eval_sql",
                "condition_at",
                "events",
                "start_page",
            )
        }
        body["events"] = body["events"][:1]
        timings = []
        for _ in range(rounds):
            started = time.perf_counter()
            client.get("/close")
            response = client.post("/init", body, content_type="application/json")
            timings.append((time.perf_counter() - started) * 1000)
            if response.status_code != 200:
                raise CommandError(
                    f"/init failed during the reset benchmark: {response.content[:200]!r}"
                )
        client.get("/close")
        return statistics.median(timings)
