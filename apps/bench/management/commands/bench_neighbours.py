"""Benchmark fair sharing: one run's page latency while another run's client floods the server.

Two runs of MicroMail's dev scenario (virtual clocks: nothing changes), one Daphne. First the
quiet run's pages alone (one client, one request at a time), then the same while a separate
process keeps `--in-flight` requests to the other run's pages open. stdout gets one line:

    bench_neighbours: alone_p95_ms=<f> flooded_p95_ms=<f> flood_pages_per_s=<f> requests=<n>

Target: flooded_p95_ms ≤ 50 (the issue's figure for a quiet 2-core machine).
"""

from __future__ import annotations

import subprocess
import sys
import time

import httpx
from django.core.management.base import BaseCommand, CommandError

from apps.kit.links import environment_root
from apps.scenarios.library import get_dev_scenario
from events import lifecycle
from events.commands import current_state
from events.models import ClockMode
from events.registry import get_environment
from sentinel_site.figures import percentile
from sentinel_site.site_server import ServerDidNotStart, site_server

ENVIRONMENT = "micromail"


def timed_pages(base_url: str, pages: list[str], seconds: float) -> list[float]:
    timings = []
    deadline = time.perf_counter() + seconds
    with httpx.Client(base_url=base_url, timeout=30) as client:
        position = 0
        while time.perf_counter() < deadline:
            started = time.perf_counter()
            response = client.get(pages[position % len(pages)])
            if response.status_code != 200:
                raise CommandError(f"GET {response.url} answered {response.status_code}")
            timings.append((time.perf_counter() - started) * 1000)
            position += 1
    return timings


class Command(BaseCommand):
    help = "Time one run's pages while another run's client floods the server."

    def add_arguments(self, parser):
        parser.add_argument("--seconds", type=float, default=10.0, help="of each phase")
        parser.add_argument("--in-flight", type=int, default=24, help="the flood's requests")

    def handle(self, *args, seconds: float, in_flight: int, **options):
        if seconds <= 0 or in_flight < 1:
            raise CommandError(
                f"--seconds must be > 0 and --in-flight ≥ 1, got {seconds:g}, {in_flight}"
            )
        spec = get_dev_scenario(ENVIRONMENT).to_run_spec()
        quiet, noisy = (lifecycle.create_run(spec, clock_mode=ClockMode.VIRTUAL) for _ in range(2))
        sample = get_environment(ENVIRONMENT).sample_pages
        assert sample is not None

        def pages(run) -> list[str]:
            return [f"{environment_root(run)}/{page}" for page in sample(current_state(run))]

        try:
            with site_server() as base_url:
                timed_pages(base_url, pages(quiet) + pages(noisy), 2.0)  # warm both
                alone = timed_pages(base_url, pages(quiet), seconds)
                flood = subprocess.Popen(
                    [sys.executable, "-m", "apps.bench.flood", base_url, *pages(noisy),
                     "--in-flight", str(in_flight), "--seconds", str(seconds + 1)],
                    stdout=subprocess.PIPE, text=True,
                )  # fmt: skip
                time.sleep(0.5)  # let the flood fill the server's lines before timing
                flooded = timed_pages(base_url, pages(quiet), seconds)
                out, _ = flood.communicate(timeout=seconds + 60)
        except ServerDidNotStart as exc:
            raise CommandError(str(exc)) from None
        finally:
            lifecycle.close(quiet)
            lifecycle.close(noisy)
        counts = dict(part.split("=") for part in out.split(":", 1)[1].split())
        self.stdout.write(
            f"bench_neighbours: alone_p95_ms={percentile(alone, 95):.2f} "
            f"flooded_p95_ms={percentile(flooded, 95):.2f} "
            f"flood_pages_per_s={int(counts['pages']) / (seconds + 1):.1f} "
            f"requests={len(flooded)}"
        )
        if int(counts["errors"]):
            raise CommandError(f"the flood saw {counts['errors']} failed requests")
