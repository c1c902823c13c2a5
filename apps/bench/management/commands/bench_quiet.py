"""Measure how often open pages are pushed when nothing happens: live pushes per minute with no
event due, for every sample page of every environment.

    python manage.py bench_quiet [--env microtube …] [--seconds 60] [--speed 1]

Starts the site (sentinel_site.site_server), creates one live run per environment playing its
dev.json world (everything loaded at t=0, no event after it), opens the task URL (which starts
the clock), then loads each of the environment's `sample_pages` and subscribes a websocket to
it exactly as the page's own client does (its URL, log position and due time). For `--seconds`
of wall time it counts the frames that carry regions (a frame that only moves the page's log
position swaps nothing and is not counted). What is left is what the clock alone causes: the
top bar's minute, relative times, counts that move between events, and any render that pushes
what reads the same. A page that pushes more than once a simulated minute without a cause is
an agent woken for nothing (issue 28).

Progress and one line per page go to stderr; stdout has one line per environment and ends
with exactly one line:

    bench_quiet: max_pushes_per_min=<f> worst=<env>/<page>
"""

from __future__ import annotations

import asyncio
import json
import os
import re
from pathlib import Path

from django.conf import settings
from django.core.management import call_command
from django.core.management.base import BaseCommand, CommandError

from apps.kit.probe import state_at_time
from apps.scenarios.format import SENTINELBENCH_ENVIRONMENTS, load_dev_scenario
from events.registry import environment_names, get_environment
from sentinel_site.site_server import ServerDidNotStart, site_server

LIVE_DIV = re.compile(
    r'id="sentinel-live"[^>]*data-socket="([^"]+)"[^>]*data-seq="(\d+)"[^>]*data-due="([^"]*)"'
)
QUIET_S = 3600.0  # the runs' timeline: far longer than any measurement


def quiet_scenario(environment: str) -> dict:
    """The environment's dev.json world as a no-op scenario: loaded at 0, nothing after."""
    dev = load_dev_scenario(settings.SENTINEL_SCENARIO_DIR, environment)
    return {
        "id": f"bench-quiet-{environment}",
        "environment": environment,
        "start_page": f"HOST_ADDRESS/{environment}",
        "prompt": "bench_quiet",
        "condition_at": None,
        "event_timeline_end": QUIET_S,
        "kill_at": QUIET_S,
        "events": list(dev.events),
        "taxonomy": {},
    }


class Command(BaseCommand):
    help = "Count live pushes per minute of every sample page with no event due."

    def add_arguments(self, parser):
        parser.add_argument(
            "--env", action="append", help="environment (repeatable; default: all ten)"
        )
        parser.add_argument("--seconds", type=float, default=60.0, help="wall seconds watched")
        parser.add_argument("--speed", type=float, default=1.0, help="the runs' speed factor")

    def handle(self, *args, env, seconds, speed, **options):
        names = env or [n for n in SENTINELBENCH_ENVIRONMENTS if n in environment_names()]
        unknown = [n for n in names if n not in environment_names()]
        if unknown:
            valid = ", ".join(environment_names())
            raise CommandError(f"unknown --env {', '.join(map(repr, unknown))}; valid: {valid}")
        for name, value in (("seconds", seconds), ("speed", speed)):
            if not value > 0:
                raise CommandError(f"--{name} must be > 0, got {value}")
        call_command("migrate", verbosity=0, interactive=False)
        pages = {name: sample_paths(name) for name in names}
        try:
            log = Path(settings.BASE_DIR) / "var" / "bench-quiet.log"
            with site_server(log_path=log) as base_url:
                counts = asyncio.run(
                    Quiet(base_url.removeprefix("http://"), pages, seconds, speed, self).main()
                )
        except ServerDidNotStart as exc:
            raise CommandError(str(exc)) from None
        # Per simulated minute: at speed 2 a wall minute holds two of them.
        minutes = seconds * speed / 60.0
        rates = {key: pushes / minutes for key, pushes in counts.items()}
        for name in names:
            own = {k: r for k, r in rates.items() if k[0] == name}
            if own:
                (_, page), rate = max(own.items(), key=lambda item: item[1])
                self.stdout.write(
                    f"bench_quiet: {name} pages={len(own)} "
                    f"max_pushes_per_min={rate:.1f} worst=/{page}"
                )
        if not rates:
            raise CommandError("no page was measured")
        (name, page), worst = max(rates.items(), key=lambda item: item[1])
        self.stdout.write(f"bench_quiet: max_pushes_per_min={worst:.1f} worst={name}/{page}")


def sample_paths(environment: str) -> list[str]:
    """The environment's sample pages over its dev world (paths under its root)."""
    dev = load_dev_scenario(settings.SENTINEL_SCENARIO_DIR, environment)
    sample = get_environment(environment).sample_pages
    if sample is None:
        raise CommandError(f"{environment} declares no sample_pages")
    return list(dict.fromkeys(sample(state_at_time(environment, dev.events, 0.0))))


class Quiet:
    def __init__(self, host: str, pages: dict[str, list[str]], seconds, speed, command):
        self.host, self.pages, self.seconds, self.speed = host, pages, seconds, speed
        self.command = command
        self.counting = asyncio.Event()

    def say(self, text: str) -> None:
        self.command.stderr.write(f"bench_quiet: {text}")

    async def main(self) -> dict[tuple[str, str], int]:
        import httpx

        counts: dict[tuple[str, str], int] = {}
        async with httpx.AsyncClient(base_url=f"http://{self.host}", timeout=60) as http:
            subscriptions = []
            for environment, paths in self.pages.items():
                run = await self.start(http, environment)
                root = run["task_url"].split(self.host, 1)[-1].rsplit("/", 1)[0]
                for path in paths:
                    subscriptions.append((environment, path, f"{root}/{environment}/{path}"))
            stop = asyncio.Event()
            opened: list[asyncio.Event] = []
            tasks = []
            for environment, path, url in subscriptions:
                counts[(environment, path)] = 0
                ready = asyncio.Event()
                opened.append(ready)
                tasks.append(
                    asyncio.create_task(
                        self.watch(http, environment, path, url, counts, ready, stop)
                    )
                )
            try:
                await asyncio.wait_for(asyncio.gather(*(r.wait() for r in opened)), 120)
            except TimeoutError:
                raise CommandError("the pages did not all subscribe within 120 s") from None
            self.say(
                f"{len(tasks)} pages of {len(self.pages)} environments; watching {self.seconds:g} s"
            )
            # Loading the pages acted (opening a message reads it) and pushed the pages already
            # open: a cause. The count starts once every page is open and nothing more is done.
            self.counting.set()
            await asyncio.sleep(self.seconds)
            stop.set()
            await asyncio.gather(*tasks, return_exceptions=True)
        for (environment, path), pushes in sorted(counts.items()):
            self.say(f"{environment}/{path}: {pushes} pushes")
        return counts

    async def start(self, http, environment: str) -> dict:
        response = await http.post(
            "/api/runs/",
            json={"scenario_json": quiet_scenario(environment), "speed_factor": self.speed},
        )
        if response.status_code >= 400:
            raise CommandError(
                f"creating a {environment} run answered {response.status_code}: "
                f"{response.text[:300]}"
            )
        run = response.json()
        # Opening the task URL starts the clock, as an agent's first look does.
        await http.get(run["task_url"].split(self.host, 1)[-1], follow_redirects=True)
        return run

    async def watch(self, http, environment, path, url, counts, ready, stop) -> None:
        import websockets

        response = await http.get(url)
        found = LIVE_DIV.search(response.text)
        if response.status_code != 200 or found is None:
            self.say(f"{environment}/{path}: no live page ({response.status_code})")
            ready.set()
            return
        socket, seq, due = found.group(1), int(found.group(2)), found.group(3)
        page_url = url  # as the browser's location: path and query
        async with websockets.connect(f"ws://{self.host}{socket}", max_size=None) as ws:
            hello = {"url": page_url, "seq": seq, "due": float(due) if due else None}
            await ws.send(json.dumps(hello))
            ready.set()
            while not stop.is_set():
                try:
                    frame = await asyncio.wait_for(ws.recv(), 0.5)
                except TimeoutError:
                    continue
                message = json.loads(frame)
                if not self.counting.is_set():
                    continue
                if message.get("type") == "regions" and message.get("html"):
                    counts[(environment, path)] += 1
                    if os.environ.get("BENCH_QUIET_DEBUG"):
                        self.say(
                            f"{environment}/{path} push seq={message['seq']} due={message['next_change']}"
                        )
