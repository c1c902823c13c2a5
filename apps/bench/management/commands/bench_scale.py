"""Load like a hundred real agents: many live runs on paper-like timelines, one agent each.

    python manage.py bench_scale --runs 100 --rate 1 --seconds 60 [--processes N] [--find-knee]

Creates `--runs` live runs of the environment's own scenarios (round-robin) at `--speed`, each
moved first to a point of its timeline from which `--seconds` still fit,
starts a real server — embedded defaults (one Daphne, its in-process ticker) or, with
`--processes N`, the production shape (N Daphnes and a ticker process under supervisord; needs
REDIS_URL) — and lets one open-loop agent per run open its task URL, then load one of the run's
sample pages `--rate` times a second and perform one of the scenarios' solution steps every
`--act-every` seconds, for `--seconds`. stdout ends with exactly one line:

    bench_scale: runs=… rate=… page_p95_ms=… lateness_p99_ms=… errors=… lost=… rss_mib=… …

page latency counts from each request's scheduled moment; lateness is the recorded lateness of
every timeline entry fired meanwhile (by the ticker or by a page that read it first); `errors`
are failed or non-200 pages and 5xx actions (an action the run refuses, 4xx, is counted apart);
`lost` = timeline entries due by the end that did not fire exactly once + acknowledged actions
missing from the log; `rss_mib` = the most resident memory the server's processes held together.
`--find-knee` doubles the rate from `--rate` until page p95 passes 100 ms and reports where.
"""

from __future__ import annotations

import contextlib
import random
import threading
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

from django.conf import settings
from django.core.management import call_command
from django.core.management.base import BaseCommand, CommandError
from django.db.models import Count

from apps.bench.load import AgentPlan, LoadResult, OpenLoop
from apps.kit.links import contact_path, environment_root, task_path
from apps.kit.probe import state_at_time
from apps.scenarios.library import scenario_library
from events import lifecycle
from events.clock import wall_now
from events.commands import current_state
from events.models import Event, EventKind, Run
from events.registry import environment_names, get_environment
from events.timing import SpeedFactorError, validate_speed_factor
from sentinel_site.figures import percentile
from sentinel_site.processes import descendants, rss_kib
from sentinel_site.site_server import ServerDidNotStart, site_server

KNEE_MS = 100.0  # page p95 beyond this is where the server "breaks"
KNEE_STEPS = 6
DUE_GRACE_S = 1.0  # entries due this close to the end may still be in flight: not counted


@dataclass(frozen=True)
class Figures:
    rate: float
    page_p95_ms: float
    lateness_p99_ms: float
    errors: int
    lost: int
    requests: int
    acknowledged: int
    refused: int


class Command(BaseCommand):
    help = "Load the site like many real agents on many live runs; report pages, lateness, losses."

    def add_arguments(self, parser):
        parser.add_argument("--runs", type=int, default=100, help="live runs, one agent each")
        parser.add_argument("--rate", type=float, default=1.0, help="pages per second per agent")
        parser.add_argument("--seconds", type=float, default=60.0, help="wall seconds of load")
        parser.add_argument("--speed", type=float, default=4.0, help="speed factor of every run")
        parser.add_argument("--env", default="micromail", help="environment whose scenarios run")
        parser.add_argument(
            "--act-every", type=float, default=10.0, help="seconds between an agent's actions"
        )
        parser.add_argument(
            "--processes",
            type=int,
            default=0,
            help="0: embedded defaults (one Daphne); N: the production shape with N Daphnes",
        )
        parser.add_argument(
            "--ticker", default="process", help="production shape's ticker: process or celery"
        )
        parser.add_argument(
            "--find-knee",
            action="store_true",
            help=f"double the rate until page p95 passes {KNEE_MS:g} ms",
        )

    def handle(self, *args, runs, rate, seconds, speed, env, act_every, processes, **options):
        try:
            speed = validate_speed_factor(speed)
        except SpeedFactorError as exc:
            raise CommandError(str(exc)) from None
        for name, value in (("runs", runs), ("rate", rate), ("seconds", seconds)):
            if not value > 0:
                raise CommandError(f"--{name} must be > 0, got {value:g}")
        if not act_every > 0 or processes < 0:
            raise CommandError(
                f"--act-every must be > 0 and --processes ≥ 0, got {act_every:g}, {processes}"
            )
        if env not in environment_names():
            raise CommandError(f"unknown --env {env!r}; valid: {', '.join(environment_names())}")
        scenarios = [s for s in scenario_library().values() if s.environment == env]
        if not scenarios:
            raise CommandError(f"no {env} scenarios in {settings.SENTINEL_SCENARIO_DIR}")
        call_command("migrate", verbosity=0, interactive=False)

        self.env, self.scenarios, self.speed, self.act_every = env, scenarios, speed, act_every
        shape = f"production-{processes}" if processes else "embedded"
        steps = [rate * 2**i for i in range(KNEE_STEPS)] if options["find_knee"] else [rate]
        results: list[Figures] = []
        with self.server(processes, options["ticker"]) as base_url, RssSampler() as rss:
            for step in steps:
                figures = self.measure(base_url, runs, step, seconds)
                results.append(figures)
                self.stderr.write(
                    f"bench_scale: rate={step:g} ({runs * step:g} pages/s) "
                    f"page_p95_ms={figures.page_p95_ms:.2f} "
                    f"lateness_p99_ms={figures.lateness_p99_ms:.2f} errors={figures.errors} "
                    f"lost={figures.lost} actions={figures.acknowledged} refused={figures.refused}"
                )
                if figures.page_p95_ms > KNEE_MS or figures.errors:
                    break
        first = results[0]
        line = (
            f"bench_scale: runs={runs} rate={first.rate:g} page_p95_ms={first.page_p95_ms:.2f} "
            f"lateness_p99_ms={first.lateness_p99_ms:.2f} errors={first.errors} "
            f"lost={first.lost} rss_mib={rss.peak_mib:.0f} requests={first.requests} "
            f"shape={shape}"
        )
        if options["find_knee"]:
            knee = next((f for f in results if f.page_p95_ms > KNEE_MS or f.errors), None)
            # The first total page rate past the knee; ">N" when even the last step held.
            where = f"{runs * knee.rate:g}" if knee else f">{runs * steps[-1]:g}"
            line += f" knee_pages_per_s={where}"
        self.stdout.write(line)

    @contextlib.contextmanager
    def server(self, processes: int, ticker: str) -> Iterator[str]:
        log = Path(settings.BASE_DIR) / "var" / "bench-scale.log"
        try:
            if processes == 0:
                with site_server(log_path=log) as url:
                    yield url
                return
            from sentinel_site.production import ProductionError, production_site

            try:
                with production_site(processes, ticker=ticker) as site:
                    yield site.base_url
            except ProductionError as exc:
                raise CommandError(str(exc)) from None
        except ServerDidNotStart as exc:
            raise CommandError(str(exc)) from None

    # --- one measurement -------------------------------------------------------------------

    def measure(self, base_url: str, runs: int, rate: float, seconds: float) -> Figures:
        created = self.create_runs(runs, seconds)
        try:
            plans = [self.plan(run) for run in created]
            result = OpenLoop(
                base_url, plans, rate=rate, seconds=seconds, act_every=self.act_every
            ).run()
            ended = wall_now()
            lost = self.lost_entries(created, ended) + self.lost_actions(result)
            lateness = list(
                Event.objects.filter(
                    run_id__in=[r.pk for r in created],
                    kind=EventKind.SCENARIO,
                    lateness_ms__isnull=False,
                ).values_list("lateness_ms", flat=True)
            )
        finally:
            for run in created:
                lifecycle.close(run)
        if result.errors:
            self.stderr.write(
                f"bench_scale: {len(result.errors)} errors; first: {result.errors[0]}"
            )
        self.stderr.write(f"bench_scale: {len(lateness)} timeline entries fired with a lateness")
        return Figures(
            rate=rate,
            page_p95_ms=percentile(result.page_ms, 95),
            lateness_p99_ms=percentile(lateness, 99),
            errors=len(result.errors),
            lost=lost,
            requests=result.requests,
            acknowledged=len(result.acknowledged),
            refused=result.refused,
        )

    def create_runs(self, runs: int, seconds: float) -> list[Run]:
        """Runs of the scenarios in turn, each moved to its own point of its timeline first (as
        agents started at different times would find them), so that within the window some
        pass their condition and their agents' solution steps are accepted."""
        rng = random.Random(42)
        created = []
        for i in range(runs):
            spec = self.scenarios[i % len(self.scenarios)].to_run_spec()
            run = lifecycle.create_run(spec, speed_factor=self.speed)
            latest = spec["event_timeline_end"] - seconds * self.speed
            if latest > 0:
                lifecycle.advance(run, round(rng.uniform(0, latest), 3))
            created.append(run)
        return created

    def plan(self, run: Run) -> AgentPlan:
        root = environment_root(run) + "/"
        pages = [root + p for p in self.lasting_pages(run)]
        own = [s for s in self.scenarios if s.id == run.scenario_id]
        steps = [
            {"action": step["action"], "payload": step.get("payload") or {}}
            for scenario in own + [s for s in self.scenarios if s not in own]
            for step in scenario.solution
        ]  # its own solution first: valid once its condition has passed
        return AgentPlan(
            run_id=run.pk,
            task_path=task_path(run),
            pages=pages or [root],
            actions_path=contact_path(run).rsplit("/", 1)[0] + "/actions",
            actions=steps,
        )

    def lasting_pages(self, run: Run) -> list[str]:
        """The run's sample pages now that are still pages at its timeline's end: a page of an
        item an event retracts meanwhile (a recalled mail's reply form) rightly answers 404 once
        the item is gone, which is neither an error of the server nor load worth measuring."""
        sample_pages = get_environment(self.env).sample_pages
        if not sample_pages:
            return []
        lasting = set(sample_pages(state_at_time(self.env, run.timeline, run.event_timeline_end)))
        return [page for page in sample_pages(current_state(run)) if page in lasting]

    @staticmethod
    def lost_entries(created: list[Run], ended: float) -> int:
        """Timeline entries due before the end that are not in the log exactly once.

        Read straight from the log — nothing here fires what is due, which would hide a ticker
        that stopped."""
        lost = 0
        for run in Run.objects.filter(pk__in=[r.pk for r in created]):
            if run.started_at is None:
                lost += sum(1 for e in run.timeline if e["time"] > 0)  # never started
                continue
            due = {
                index
                for index, entry in enumerate(run.timeline)
                if 0 < entry["time"] <= run.event_timeline_end
                and run.started_at + entry["time"] / run.speed_factor <= ended - DUE_GRACE_S
            }
            counts = dict(
                Event.objects.filter(run_id=run.pk, timeline_index__in=due)
                .values_list("timeline_index")
                .annotate(n=Count("seq"))
            )
            lost += sum(1 for index in due if counts.get(index) != 1)
        return lost

    @staticmethod
    def lost_actions(result: LoadResult) -> int:
        if not result.acknowledged:
            return 0
        logged = set(
            Event.objects.filter(
                run_id__in={run for run, _ in result.acknowledged}, kind=EventKind.ACTION
            ).values_list("run_id", "seq")
        )
        return sum(1 for ack in result.acknowledged if ack not in logged)


class RssSampler:
    """The peak total resident memory of this process's children (the servers), sampled 1/s."""

    def __init__(self, every_s: float = 1.0) -> None:
        self.every_s = every_s
        self.peak_mib = 0.0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._sample, name="rss-sampler", daemon=True)

    def __enter__(self) -> RssSampler:
        self._thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self._stop.set()
        self._thread.join(timeout=5)

    def _sample(self) -> None:
        import os

        while not self._stop.wait(self.every_s):
            total_kib = sum(rss_kib(pid) for pid in descendants(os.getpid()))
            self.peak_mib = max(self.peak_mib, total_kib / 1024)
