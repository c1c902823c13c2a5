"""Measure live push latency: event fired on the server → update received by every subscriber.

    python manage.py bench_live [--env micromail] --clients 50 --seconds 30 [--rate 2] [--runs 1]

Starts the site (sentinel_site.site_server) over the configured database and settings (so it
measures whichever shape the environment selects: embedded, or Redis + Celery), creates
virtual-clock runs of `--env` through the multi-run API, subscribes `--clients` websocket
clients to its start page (round-robin over `--runs` runs), then advances every run through
`/api/runs/<id>/advance/` `--rate` times a second, each advance firing one scenario event.

The timeline is the environment's own material, so any registered environment can be measured:
the preload of its scenario with the most events, then every later event of all its scenarios
in turn (an event delivering what is already there changes nothing but is pushed all the same).
Latency per (event, client) = wall time the client received the first update including the
event − the event's `recorded_at`. Progress goes to stderr; stdout ends with exactly one line:

    bench_live: push_p50_ms=<f> push_p99_ms=<f> messages=<n>
"""

from __future__ import annotations

import asyncio
import json
import re
import time

from django.conf import settings
from django.core.management import call_command
from django.core.management.base import BaseCommand, CommandError

from apps.scenarios.library import scenario_library
from events.registry import environment_names
from sentinel_site.figures import percentile
from sentinel_site.site_server import ServerDidNotStart, site_server

SEQ = re.compile(r'"seq": (\d+)')
LIVE_SOCKET = re.compile(r'id="sentinel-live"[^>]*data-socket="([^"]+)"')
# Generous: on a fully loaded 2-core machine a page render and a first push take seconds.
SUBSCRIBE_S = 120.0


def bench_scenario(environment: str, events: int) -> dict:
    """A no-op scenario of `environment`: a realistic preload at t=0, then one of its own
    scenario events per simulated second."""
    own = [s for s in scenario_library().values() if s.environment == environment]
    if not own:
        raise CommandError(f"no scenarios for {environment!r} in {settings.SENTINEL_SCENARIO_DIR}")
    busiest = max(own, key=lambda s: sum(1 for e in s.events if e["time"] > 0))
    preload = [e for e in busiest.events if e["time"] <= 0]
    stream = [e for s in own for e in s.events if e["time"] > 0]
    if not stream:
        raise CommandError(f"the {environment} scenarios have no events after t=0 to fire")
    return {
        "id": "bench-live",
        "environment": environment,
        "start_page": busiest.start_page,
        "prompt": "bench_live",
        "condition_at": None,
        "event_timeline_end": float(events + 10),
        "kill_at": float(events + 10),
        "events": [{**e, "time": 0.0} for e in preload]
        + [{**stream[(i - 1) % len(stream)], "time": float(i)} for i in range(1, events + 1)],
        "eval_sql": "SELECT 1",
        "taxonomy": {"milestone_type": "absolute", "monitoring_approach": "passive"},
    }


class Command(BaseCommand):
    help = "Measure websocket push latency of live pages (event fired → update received)."

    def add_arguments(self, parser):
        parser.add_argument("--env", default="micromail", help="environment name")
        parser.add_argument("--clients", type=int, default=50, help="websocket subscribers")
        parser.add_argument("--seconds", type=float, default=30.0, help="how long to fire events")
        parser.add_argument("--rate", type=float, default=2.0, help="advances per second (per run)")
        parser.add_argument("--runs", type=int, default=1, help="runs the clients are spread over")

    def handle(self, *args, env, clients, seconds, rate, runs, **options):
        if env not in environment_names():
            raise CommandError(f"unknown --env {env!r}; valid: {', '.join(environment_names())}")
        for name, value in (
            ("clients", clients),
            ("seconds", seconds),
            ("rate", rate),
            ("runs", runs),
        ):
            if not value > 0:
                raise CommandError(f"--{name} must be > 0, got {value}")
        if runs > clients:
            raise CommandError(f"--runs ({runs}) cannot exceed --clients ({clients})")
        try:
            import websockets  # noqa: F401
        except ImportError:
            raise CommandError(
                "bench_live needs the `websockets` package: pip install websockets"
            ) from None
        call_command("migrate", verbosity=0, interactive=False)
        events = int(seconds * rate) + 5
        scenario = bench_scenario(env, events)
        try:
            with site_server(log_path=settings.BASE_DIR / "var" / "bench-live.log") as base_url:
                result = asyncio.run(
                    Bench(
                        base_url.removeprefix("http://"),
                        scenario,
                        clients,
                        seconds,
                        rate,
                        runs,
                        self.stderr,
                    ).main()
                )
        except ServerDidNotStart as exc:
            raise CommandError(str(exc)) from None
        latencies, messages, missed = result
        if missed:
            self.stderr.write(f"bench_live: {missed} (event, client) updates never arrived")
        if latencies:
            self.stderr.write(
                f"bench_live: {len(latencies)} (event, client) pairs; p90="
                f"{percentile(latencies, 90):.1f} ms, max={max(latencies):.1f} ms"
            )
        self.stdout.write(
            f"bench_live: push_p50_ms={percentile(latencies, 50):.2f} "
            f"push_p99_ms={percentile(latencies, 99):.2f} messages={messages}"
        )


class Bench:
    def __init__(self, host, scenario, clients, seconds, rate, runs, stderr):
        self.host, self.scenario = host, scenario
        self.clients, self.seconds, self.rate, self.runs = clients, seconds, rate, runs
        self.stderr = stderr

    def say(self, text: str) -> None:
        self.stderr.write(f"bench_live: {text}")

    async def api(self, http, path: str, body: dict) -> dict:
        response = await http.post(path, json=body)
        if response.status_code >= 400:
            raise CommandError(
                f"POST {path} answered {response.status_code}: {response.text[:300]}"
            )
        return response.json()

    async def client(self, run: dict, received: list, ready: asyncio.Event, stop: asyncio.Event):
        import httpx
        import websockets

        # The run's task URL redirects to its start page; its live socket is named in the page.
        async with httpx.AsyncClient(base_url=f"http://{self.host}") as http:
            response = await http.get(
                run["task_url"].split(self.host, 1)[-1], follow_redirects=True
            )
        url = response.url.raw_path.decode()
        socket = LIVE_SOCKET.search(response.text).group(1)
        async with websockets.connect(f"ws://{self.host}{socket}", max_size=None) as ws:
            await ws.send(json.dumps({"url": url, "seq": 0}))
            await ws.recv()  # seq 0 is behind the preload: the first push is the warm-up
            ready.set()
            closer = asyncio.create_task(self.close_on(stop, ws))
            try:
                async for frame in ws:
                    at = time.time()  # on arrival; the header is read without parsing the HTML
                    found = SEQ.search(frame, 0, 400)
                    if found and '"type": "regions"' in frame[:400]:
                        received.append((int(found.group(1)), at))
            finally:
                closer.cancel()

    @staticmethod
    async def until_subscribed(clients: list[asyncio.Task], ready: list[asyncio.Event]) -> None:
        """Every client subscribed, or a clear error: the one a client failed with (not a
        timeout hiding it), else how many subscribed within SUBSCRIBE_S."""
        everyone = asyncio.ensure_future(asyncio.gather(*(r.wait() for r in ready)))
        done, _ = await asyncio.wait(
            [everyone, *clients], timeout=SUBSCRIBE_S, return_when=asyncio.FIRST_COMPLETED
        )
        failed = [c for c in clients if c.done() and c.exception() is not None]
        if failed:
            everyone.cancel()
            raise CommandError(f"a websocket client failed to subscribe: {failed[0].exception()!r}")
        if everyone not in done:
            everyone.cancel()
            joined = sum(r.is_set() for r in ready)
            raise CommandError(
                f"the websocket clients did not all subscribe within {SUBSCRIBE_S:g} s "
                f"({joined}/{len(ready)} did)"
            )

    @staticmethod
    async def close_on(stop: asyncio.Event, ws) -> None:
        await stop.wait()
        await ws.close()

    async def main(self) -> tuple[list[float], int, int]:
        import httpx

        async with httpx.AsyncClient(base_url=f"http://{self.host}", timeout=60) as http:
            runs = [
                await self.api(
                    http, "/api/runs/", {"scenario_json": self.scenario, "clock_mode": "virtual"}
                )
                for _ in range(self.runs)
            ]
            stop = asyncio.Event()
            inboxes = [(runs[i % self.runs], [], asyncio.Event()) for i in range(self.clients)]
            tasks = [
                asyncio.create_task(self.client(run, received, ready, stop))
                for run, received, ready in inboxes
            ]
            await self.until_subscribed(tasks, [ready for _, _, ready in inboxes])
            self.say(
                f"{self.clients} clients subscribed to {self.runs} run(s); firing "
                f"{self.rate:g}/s for {self.seconds:g} s"
            )
            started = time.monotonic()
            tick = 0
            while time.monotonic() - started < self.seconds:
                tick += 1
                await asyncio.gather(
                    *(
                        self.api(http, f"/api/runs/{run['id']}/advance/", {"time": float(tick)})
                        for run in runs
                    )
                )
                await asyncio.sleep(max(0.0, started + tick / self.rate - time.monotonic()))
            await asyncio.sleep(2.0)  # let the last pushes land
            stop.set()
            await asyncio.gather(*tasks, return_exceptions=True)
            fired = {}
            for run in runs:
                log = (await http.get(f"/api/runs/{run['id']}/events/")).json()
                fired[run["id"]] = [
                    (e["seq"], e["recorded_at"])
                    for e in log
                    if e["kind"] == "scenario" and e["at"] > 0
                ]
                await self.api(http, f"/api/runs/{run['id']}/close/", {})
        latencies, messages, missed = [], 0, 0
        for run, received, _ in inboxes:
            messages += len(received)
            for seq, recorded_at in fired[run["id"]]:
                arrival = next((at for got, at in received if got >= seq), None)
                if arrival is None:
                    missed += 1
                else:
                    latencies.append((arrival - recorded_at) * 1000.0)
        return latencies, messages, missed
