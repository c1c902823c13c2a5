"""Benchmark an environment's pages as agents see them: a real server, concurrent keep-alive clients.

Creates a run of the environment's dev scenario (virtual clock, so the state holds still), asks
the environment for its sample pages, starts Daphne on the configured database, and lets
`--clients` threads GET those pages round-robin for `--seconds`. Every page is fetched once
before timing starts (template loading, the first open of a message). Per-page figures go to
stderr; stdout gets exactly one line:

    bench_pages: env=micromail p50_ms=<f> p95_ms=<f> requests=<n>
"""

from __future__ import annotations

import statistics
import threading
import time
from collections import defaultdict
from dataclasses import dataclass, field

import httpx
from django.core.management.base import BaseCommand, CommandError
from django.db import DatabaseError

from apps.kit.links import environment_root
from apps.scenarios.format import ScenarioError
from apps.scenarios.library import get_dev_scenario
from events import lifecycle
from events.commands import current_state
from events.models import ClockMode, Run
from events.registry import all_environments, environment_names, get_environment
from sentinel_site.figures import percentile
from sentinel_site.site_server import ServerDidNotStart, site_server


@dataclass
class Tally:
    """One client's timings, merged after the run (no locking on the hot path)."""

    by_page: dict[str, list[float]] = field(default_factory=lambda: defaultdict(list))
    failures: list[str] = field(default_factory=list)


def benchable() -> list[str]:
    return [env.name for env in all_environments() if env.sample_pages is not None]


class Command(BaseCommand):
    help = "Time an environment's pages under concurrent keep-alive clients against a real server."

    def add_arguments(self, parser):
        parser.add_argument("--env", required=True, help="environment name, e.g. micromail")
        parser.add_argument("--seconds", type=float, default=30.0, help="wall seconds of load")
        parser.add_argument("--clients", type=int, default=8, help="concurrent client threads")

    def handle(self, *args, env: str, seconds: float, clients: int, **options):
        if env not in benchable():
            known = ", ".join(benchable()) or "none"
            if env in environment_names():
                raise CommandError(f"--env {env!r} declares no sample_pages; valid: {known}")
            raise CommandError(f"unknown --env {env!r}; valid: {known}")
        if seconds <= 0 or clients < 1:
            raise CommandError(
                f"--seconds must be > 0 and --clients ≥ 1, got {seconds:g} and {clients}"
            )

        run = self._create_run(env)
        try:
            root = environment_root(run) + "/"
            pages = [root + page for page in get_environment(env).sample_pages(current_state(run))]
            if not pages:
                raise CommandError(f"{env}.sample_pages returned no pages for its dev scenario")
            try:
                with site_server() as base_url:
                    self._warm_up(base_url, pages)
                    tallies = self._load(base_url, pages, seconds, clients)
            except ServerDidNotStart as exc:
                raise CommandError(str(exc)) from None
        finally:
            lifecycle.close(run)

        timings = [t for tally in tallies for page in tally.by_page.values() for t in page]
        failures = [f for tally in tallies for f in tally.failures]
        self._report_pages(root, tallies)
        self.stdout.write(
            f"bench_pages: env={env} p50_ms={percentile(timings, 50):.2f} "
            f"p95_ms={percentile(timings, 95):.2f} requests={len(timings)}"
        )
        if failures:
            raise CommandError(f"{len(failures)} requests failed; first: {failures[0]}")

    def _create_run(self, env: str) -> Run:
        try:
            spec = get_dev_scenario(env).to_run_spec()
        except (FileNotFoundError, ScenarioError) as exc:
            raise CommandError(str(exc)) from None
        try:
            return lifecycle.create_run(spec, clock_mode=ClockMode.VIRTUAL)
        except DatabaseError as exc:
            raise CommandError(
                f"the database is not ready ({exc}); run: manage.py migrate"
            ) from None

    def _warm_up(self, base_url: str, pages: list[str]) -> None:
        with httpx.Client(base_url=base_url, timeout=30) as client:
            for page in pages:
                response = client.get(page)
                if response.status_code != 200:
                    raise CommandError(
                        f"GET {page} answered {response.status_code} before timing began"
                    )

    def _load(self, base_url: str, pages: list[str], seconds: float, clients: int) -> list[Tally]:
        tallies = [Tally() for _ in range(clients)]
        ready = threading.Barrier(clients + 1)
        deadline = [0.0]

        def client_loop(index: int) -> None:
            tally = tallies[index]
            with httpx.Client(base_url=base_url, timeout=30) as client:
                position = index * len(pages) // clients  # spread clients over the pages
                ready.wait()
                while time.perf_counter() < deadline[0]:
                    page = pages[position % len(pages)]
                    position += 1
                    started = time.perf_counter()
                    try:
                        response = client.get(page)
                    except httpx.HTTPError as exc:
                        tally.failures.append(f"GET {page}: {exc!r}")
                        break  # the server is gone or stuck: retrying would only spin
                    elapsed_ms = (time.perf_counter() - started) * 1000
                    if response.status_code != 200:
                        tally.failures.append(f"GET {page} answered {response.status_code}")
                        continue
                    tally.by_page[page].append(elapsed_ms)

        threads = [
            threading.Thread(target=client_loop, args=(i,), daemon=True) for i in range(clients)
        ]
        for thread in threads:
            thread.start()
        deadline[0] = time.perf_counter() + seconds
        ready.wait()
        for thread in threads:
            thread.join()
        return tallies

    def _report_pages(self, root: str, tallies: list[Tally]) -> None:
        merged: dict[str, list[float]] = defaultdict(list)
        for tally in tallies:
            for page, timings in tally.by_page.items():
                merged[page].extend(timings)
        for page, timings in sorted(merged.items(), key=lambda item: -statistics.median(item[1])):
            self.stderr.write(
                f"  {page.removeprefix(root) or './':<48} n={len(timings):<6} "
                f"p50_ms={percentile(timings, 50):7.2f} p95_ms={percentile(timings, 95):7.2f}"
            )
