"""Benchmark the harness protocol as the original's scripts drive it, over HTTP, on a real server.

    python manage.py bench_protocol [--env micromail …] [--quick]

Starts the site on embedded defaults (sentinel_site.site_server: one Daphne, its ticker and
sandbox workers), but for a run-creation limit fit for one client making every run
(CREATION_RATE), and measures, with keep-alive clients, on each environment's scenario with the
largest preload (its "full preload"):

- reset: `GET /close` + `POST /init` of that scenario, and `POST /evaluate` of the fresh run —
  medians per environment;
- `/status` p99 while a live run's clock runs;
- landing pages per second: the run's start page (virtual clock, so it holds still) loaded by 8
  keep-alive clients;
- server CPU per pushed frame: 50 websocket watchers on the first environment's landing page
  of a live run whose inbox gets an arrival every 2 s (its own later events, repeated), CPU of
  the server and its workers ÷ frames received, event and clock-driven pushes alike;
- RSS growth: resident memory of the server and its workers before and after 1,000 runs are
  created, opened (task URL, start page) and closed.

First, before the site starts, the machine's floor (apps.bench.floor): the median and p99 of
1,000 requests, by the same keep-alive client, to a Daphne with no application work behind it. The
machines of one kind differ two- to four-fold; the floor says what any request costs on this one
(a reset is two requests), so figures from different machines can be compared.

Figures per environment and the floor go to stderr; stdout has the floor's line, then ends with
exactly one line, the worst environment for each figure:

    bench_protocol: reset_ms_median=… evaluate_ms_median=… status_ms_p99=… pages_per_s_min=…
    push_cpu_ms=… rss_growth_mib=…

`--quick` shrinks every count and duration so the whole command takes seconds (its test).

On embedded defaults (SQLite) the server gets a fresh database of its own, deleted afterwards:
the checkout's grows by some 1,350 runs a measurement, which then list on its home page, and a
reset on a database that had served a few thousand runs measured up to half as slow again.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import httpx
from django.conf import settings
from django.core.management import call_command
from django.core.management.base import BaseCommand, CommandError
from django.db import connection

from apps.scenarios.library import scenario_library
from events.registry import environment_names
from sentinel_site.figures import percentile
from sentinel_site.processes import cpu_seconds, descendants, rss_kib
from sentinel_site.site_server import ServerDidNotStart, child_environment, site_server

LIVE_SOCKET = re.compile(r'id="sentinel-live"[^>]*data-socket="([^"]+)"')
EVENT_EVERY_S = 2.0  # a watched inbox: one arrival every two seconds
SUBSCRIBE_S = 60.0  # the watchers' time to subscribe, at most
# The server's run-creation limit for this benchmark. It is one client making every run, as the
# original's scripts reset (`GET /close` + `POST /init`): ≈1,350 runs in a few minutes at full
# size (31 resets and a still run per environment, then 1,000 runs for the memory figure), past
# the default 1,000 a minute per client. The limit stays on, so its cost is in every reset timed.
CREATION_RATE = "10000/min"
FLOOR_APPLICATION = "apps.bench.floor:application"


@dataclass(frozen=True)
class Sizes:
    """How much of each measurement to take."""

    resets: int = 30
    statuses: int = 1000
    page_seconds: float = 10.0
    page_clients: int = 8
    watchers: int = 50
    watch_seconds: float = 30.0
    runs: int = 1000
    floor_requests: int = 1000


QUICK = Sizes(
    resets=3,
    statuses=50,
    page_seconds=1.0,
    page_clients=2,
    watchers=3,
    watch_seconds=2,
    runs=10,
    floor_requests=20,
)


def full_preload_scenario(environment: str) -> dict:
    """The environment's scenario with the most preload entries, as `/init` takes it."""
    own = [s for s in scenario_library().values() if s.environment == environment]
    if not own:
        raise CommandError(f"no scenarios for {environment!r} in {settings.SENTINEL_SCENARIO_DIR}")
    fullest = max(own, key=lambda s: (sum(1 for e in s.events if e["time"] <= 0), s.id))
    return fullest.to_run_spec()


def watched(spec: dict, seconds: float) -> dict:
    """`spec` as an inbox being watched: its preload, then its later arrivals again and again,
    one every EVENT_EVERY_S from the clock's start until the watch surely ended (the
    watchers subscribe first, within SUBSCRIBE_S) — pushes the watch sees whatever the
    scenario's own spacing. A no-op task: nothing is graded."""
    preload = [e for e in spec["events"] if e["time"] <= 0]
    later = [e for e in spec["events"] if e["time"] > 0] or preload
    count = int((SUBSCRIBE_S + seconds) / EVENT_EVERY_S) + 2
    stream = [{**later[i % len(later)], "time": EVENT_EVERY_S * (i + 1)} for i in range(count)]
    end = EVENT_EVERY_S * (count + 1)
    return {**spec, "events": preload + stream, "event_timeline_end": end, "condition_at": None}


@contextlib.contextmanager
def measured_database() -> Iterator[str | None]:
    """The server's database, migrated: on SQLite a fresh file of its own (its DATABASE_URL),
    else (PostgreSQL) the configured one (None)."""
    if connection.vendor != "sqlite":
        call_command("migrate", verbosity=0, interactive=False)
        yield None
        return
    with tempfile.TemporaryDirectory(prefix="bench-protocol-") as folder:
        url = f"sqlite:///{Path(folder) / 'db.sqlite3'}"
        # Migrated by a process of its own, as the server will open it: this one's connections
        # stay on the configured database (the test database under pytest).
        migrated = subprocess.run(
            [sys.executable, "manage.py", "migrate", "--noinput", "--verbosity=0"],
            cwd=settings.BASE_DIR,
            env=child_environment(url),
            capture_output=True,
            text=True,
        )
        if migrated.returncode:
            raise CommandError(f"could not migrate the benchmark's database: {migrated.stderr}")
        yield url


def server_cpu_s() -> float:
    return sum(cpu_seconds(pid) for pid in descendants(os.getpid()))


def server_rss_mib() -> float:
    return sum(rss_kib(pid) for pid in descendants(os.getpid())) / 1024


def figures_line(figures: dict[str, float]) -> str:
    return "bench_protocol: " + " ".join(f"{name}={value:.2f}" for name, value in figures.items())


class Protocol:
    """The flat endpoints, one keep-alive connection; a non-2xx answer stops the benchmark."""

    def __init__(self, base_url: str):
        self.http = httpx.Client(base_url=base_url, timeout=60)

    def call(self, method: str, path: str, **kwargs) -> httpx.Response:
        response = self.http.request(method, path, **kwargs)
        if response.status_code >= 400:
            raise CommandError(
                f"{method} {path} answered {response.status_code}: {response.text[:300]}"
            )
        return response

    def timings_ms(self, path: str, count: int) -> list[float]:
        """How long each of `count` GETs of `path` took, one after another."""
        timings = []
        for _ in range(count):
            started = time.perf_counter()
            self.call("GET", path)
            timings.append((time.perf_counter() - started) * 1000)
        return timings

    def reset(self, spec: dict, **extra) -> None:
        self.call("GET", "/close")
        self.call("POST", "/init", json={**spec, **extra})

    def open(self) -> str:
        """Start the clock through the task URL; the start page's path."""
        location = self.call("GET", "/redirect").headers["location"]
        landed = self.http.get(location, follow_redirects=True)
        if landed.status_code != 200:
            raise CommandError(f"{location} led to {landed.url} answering {landed.status_code}")
        return landed.url.raw_path.decode()

    def still_run(self, spec: dict) -> tuple[int, str]:
        """A virtual-clock run (the flat slot's task URL would start its clock) and its start
        page's path, through the multi-run API."""
        run = self.call(
            "POST", "/api/runs/", json={"scenario_json": spec, "clock_mode": "virtual"}
        ).json()
        task = httpx.URL(run["task_url"]).raw_path.decode()
        landed = self.http.get(task, follow_redirects=True)
        if landed.status_code != 200:
            raise CommandError(f"{task} led to {landed.url} answering {landed.status_code}")
        return run["id"], landed.url.raw_path.decode()


class Command(BaseCommand):
    help = "Time reset, evaluate, /status, landing pages, pushes and memory over HTTP."

    def add_arguments(self, parser):
        parser.add_argument(
            "--env", action="append", help="environment (repeatable); default: every one"
        )
        parser.add_argument("--quick", action="store_true", help="seconds, not minutes (tests)")

    def handle(self, *args, env, quick, **options):
        known = environment_names()
        envs = env or known
        for name in envs:
            if name not in known:
                raise CommandError(f"unknown --env {name!r}; valid: {', '.join(known)}")
        sizes = QUICK if quick else Sizes()
        specs = {name: full_preload_scenario(name) for name in envs}
        log = settings.BASE_DIR / "var" / "bench-protocol.log"
        try:
            with measured_database() as database_url:
                floor = self.floor(database_url, log, sizes.floor_requests)
                with site_server(
                    database_url=database_url,
                    log_path=log,
                    extra_env={"SENTINEL_RUN_CREATION_RATE": CREATION_RATE},
                ) as base_url:
                    figures = self.measure(base_url, specs, sizes)
        except ServerDidNotStart as exc:
            raise CommandError(str(exc)) from None
        self.stdout.write(figures_line(floor))
        self.stdout.write(figures_line(figures))

    def floor(self, database_url: str | None, log: Path, count: int) -> dict[str, float]:
        """The median and p99 time of a request to Daphne with nothing behind it
        (apps.bench.floor)."""
        with site_server(
            database_url=database_url, log_path=log, application=FLOOR_APPLICATION
        ) as base_url:
            protocol = Protocol(base_url)
            try:
                timings = protocol.timings_ms("/", count)
            finally:
                protocol.http.close()
        floor = {
            "floor_ms_median": statistics.median(timings),
            "floor_ms_p99": percentile(timings, 99),
        }
        self.stderr.write(
            f"{figures_line(floor)} (a request to a Daphne with nothing behind it; "
            "a reset is two requests)"
        )
        return floor

    def say(self, text: str) -> None:
        self.stderr.write(f"bench_protocol: {text}")

    def measure(self, base_url: str, specs: dict[str, dict], sizes: Sizes) -> dict[str, float]:
        protocol = Protocol(base_url)
        try:
            resets, evaluates, pages = {}, {}, {}
            for name, spec in specs.items():
                resets[name], evaluates[name] = self.resets(protocol, spec, sizes.resets)
                pages[name] = self.pages(protocol, base_url, spec, sizes)
                self.say(
                    f"{name:<13} reset_ms_median={resets[name]:6.2f} "
                    f"evaluate_ms_median={evaluates[name]:6.2f} pages_per_s={pages[name]:7.1f}"
                )
            first = next(iter(specs.values()))
            status_p99 = self.status_p99(protocol, first, sizes.statuses)
            push_cpu = self.push_cpu_ms(protocol, base_url, first, sizes)
            self.say(f"status_ms_p99={status_p99:.2f} push_cpu_ms={push_cpu:.2f}")
            growth = self.rss_growth(protocol, list(specs.values()), sizes.runs)
            protocol.call("GET", "/close")
        finally:
            protocol.http.close()
        return {
            "reset_ms_median": max(resets.values()),
            "evaluate_ms_median": max(evaluates.values()),
            "status_ms_p99": status_p99,
            "pages_per_s_min": min(pages.values()),
            "push_cpu_ms": push_cpu,
            "rss_growth_mib": growth,
        }

    def resets(self, protocol: Protocol, spec: dict, count: int) -> tuple[float, float]:
        protocol.reset(spec)  # warm-up: the first of each environment loads its catalog
        protocol.call("POST", "/evaluate")
        resets, evaluates = [], []
        for _ in range(count):
            started = time.perf_counter()
            protocol.reset(spec)
            resets.append((time.perf_counter() - started) * 1000)
            started = time.perf_counter()
            protocol.call("POST", "/evaluate")
            evaluates.append((time.perf_counter() - started) * 1000)
        return statistics.median(resets), statistics.median(evaluates)

    def status_p99(self, protocol: Protocol, spec: dict, count: int) -> float:
        protocol.reset(spec)
        protocol.call("GET", "/play")
        return percentile(protocol.timings_ms("/status", count), 99)

    def pages(self, protocol: Protocol, base_url: str, spec: dict, sizes: Sizes) -> float:
        run_id, page = protocol.still_run(spec)  # a still state: every load is alike
        try:
            return self.page_rate(base_url, page, sizes)
        finally:
            protocol.call("POST", f"/api/runs/{run_id}/close/")

    def page_rate(self, base_url: str, page: str, sizes: Sizes) -> float:
        served = [0] * sizes.page_clients
        failures: list[str] = []
        ready = threading.Barrier(sizes.page_clients + 1)
        deadline = [0.0]

        def client_loop(index: int) -> None:
            with httpx.Client(base_url=base_url, timeout=30) as client:
                ready.wait()
                while time.perf_counter() < deadline[0]:
                    try:
                        response = client.get(page)
                    except httpx.HTTPError as exc:
                        failures.append(f"GET {page}: {exc!r}")
                        return  # the server is gone or stuck: retrying would only spin
                    if response.status_code != 200:
                        failures.append(f"GET {page} answered {response.status_code}")
                        return
                    served[index] += 1

        threads = [
            threading.Thread(target=client_loop, args=(i,), daemon=True)
            for i in range(sizes.page_clients)
        ]
        for thread in threads:
            thread.start()
        started = time.perf_counter()
        deadline[0] = started + sizes.page_seconds
        ready.wait()
        for thread in threads:
            thread.join()
        if failures:
            raise CommandError(f"{len(failures)} page loads failed; first: {failures[0]}")
        return sum(served) / (time.perf_counter() - started)

    def push_cpu_ms(self, protocol: Protocol, base_url: str, spec: dict, sizes: Sizes) -> float:
        protocol.reset(watched(spec, sizes.watch_seconds))
        page = protocol.open()  # a live clock: event and clock-driven pushes both happen
        socket = LIVE_SOCKET.search(
            protocol.call("GET", page).text
        )  # the page as a browser sees it
        if socket is None:
            raise CommandError(f"{page} has no live socket to watch")
        host = base_url.removeprefix("http://")
        frames, cpu_s = asyncio.run(
            watch(f"ws://{host}{socket.group(1)}", page, sizes.watchers, sizes.watch_seconds)
        )
        self.say(f"{sizes.watchers} watchers: {frames} frames, {cpu_s:.2f} server CPU-s")
        return cpu_s * 1000 / frames if frames else float("nan")

    def rss_growth(self, protocol: Protocol, specs: list[dict], runs: int) -> float:
        before = server_rss_mib()
        for index in range(runs):
            protocol.reset(specs[index % len(specs)])
            protocol.open()
        protocol.call("GET", "/close")
        time.sleep(1.0)  # let the server finish whatever the last close set off
        after = server_rss_mib()
        self.say(f"rss_mib before={before:.1f} after={after:.1f} ({runs} runs)")
        return after - before


async def watch(url: str, page: str, watchers: int, seconds: float) -> tuple[int, float]:
    """Frames `watchers` sockets received on `page` in `seconds`, and the server's CPU-s meanwhile."""
    import websockets

    counts = [0] * watchers
    subscribed = asyncio.Event()
    joined = [0]

    async def watcher(index: int, stop: asyncio.Event) -> None:
        async with websockets.connect(url, max_size=None) as ws:
            # As a page's own client: the latest position, no clock window yet (pushed at once).
            await ws.send(json.dumps({"url": page, "seq": 0}))
            await ws.recv()
            joined[0] += 1
            if joined[0] == watchers:
                subscribed.set()
            await subscribed.wait()
            while not stop.is_set():
                try:
                    await asyncio.wait_for(ws.recv(), timeout=0.2)
                except TimeoutError:
                    continue
                counts[index] += 1

    stop = asyncio.Event()
    tasks = [asyncio.create_task(watcher(i, stop)) for i in range(watchers)]
    try:
        await asyncio.wait_for(subscribed.wait(), SUBSCRIBE_S)
    except TimeoutError:
        raise CommandError(
            f"the websocket watchers did not all subscribe within {SUBSCRIBE_S:g} s"
        ) from None
    counts[:] = [0] * watchers
    cpu_before = server_cpu_s()
    await asyncio.sleep(seconds)
    cpu_s = server_cpu_s() - cpu_before
    frames = sum(counts)
    stop.set()
    await asyncio.gather(*tasks, return_exceptions=True)
    return frames, cpu_s
