"""Benchmark the task timeline page: how long the admin takes to render a long task's timeline.

Builds a 10-minute task on the configured database — a MicroMail run (virtual clock) of
`micromail-sender-absolute-passive` played to 600 simulated seconds, with 100 agent steps: a
page view every 6 s in the run's log and a transcript of 100 model calls, every fifth a
`wait_for` with two judge questions — recorded as a benchmark task whose folder holds that
transcript. Then renders `/admin/events/run/<id>/task/` in process (the admin's own view, for a
staff user, the template rendered) `--repeat` times, and deletes what it made. stdout gets one
line:

    bench_timeline: render_ms_median=<f> render_ms_max=<f> steps=100 entries=<n> target_ms=300
"""

from __future__ import annotations

import json
import statistics
import tempfile
import time
from pathlib import Path

from django.contrib.auth.models import User
from django.core.management.base import BaseCommand, CommandError
from django.test import RequestFactory
from django.urls import resolve

from apps.bench.models import BenchmarkRun, TaskResult
from apps.bench.timeline_links import TIMELINE_PATH
from apps.kit.links import environment_root
from apps.scenarios.library import UnknownScenario, get_scenario
from events import lifecycle
from events.commands import record_view
from events.models import ClockMode, Run

SCENARIO = "micromail-sender-absolute-passive"
TASK_S = 600.0
STEPS = 100
TARGET_MS = 300.0


def write_transcript(folder: Path, root: str) -> None:
    """100 steps over the task, as the reference agent writes them (apps.browser_agent)."""
    lines = []
    step_s = TASK_S / STEPS
    for n in range(1, STEPS + 1):
        start = (n - 1) * step_s
        waits = n % 5 == 0
        line = {
            "step": n,
            "t": start / 4,
            "sim_start": start,
            "sim_time": start + step_s * 0.8,
            "url": f"http://127.0.0.1:8000{root}/?folder=inbox",
            "observation": "URL: …\nTitle: Inbox\n" + '[1] link "Inbox"\n' * 40,
            "text": None,
            "tool": "wait_for" if waits else "click",
            "arguments": {"condition": "an email from Kevin Lee", "timeout": 60}
            if waits
            else {"target": 3},
            "result": "met: false — nothing new" if waits else 'clicked [3] link "Inbox"',
            "screenshot": f"transcript/step-{n:03d}.jpg",
            "usage": {"input_tokens": 5200, "output_tokens": 40},
        }
        if waits:
            line["checks"] = [
                {
                    "sim_time": start + step_s * k / 3,
                    "blocks": ["+ Kevin Lee  Expense reports  9:42 AM\n  Inbox (12)"] * 2,
                    "met": False,
                    "why": "not the awaited mail",
                    "usage": {"input_tokens": 310, "output_tokens": 12},
                }
                for k in (1, 2)
            ]
        lines.append(json.dumps(line))
    (folder / "transcript.jsonl").write_text("\n".join(lines) + "\n", encoding="utf-8")


class Command(BaseCommand):
    help = "Time the task timeline page of a 10-minute task with 100 agent steps (target < 300 ms)."

    def add_arguments(self, parser):
        parser.add_argument("--repeat", type=int, default=20, help="renders timed (default 20)")

    def handle(self, *args, repeat: int, **options):
        if repeat < 1:
            raise CommandError(f"--repeat must be ≥ 1, got {repeat}")
        try:
            spec = get_scenario(SCENARIO).to_run_spec()
        except UnknownScenario:
            raise CommandError(f"scenario {SCENARIO} not found in the scenario folder") from None
        run = lifecycle.create_run(spec, clock_mode=ClockMode.VIRTUAL)
        benchmark = None
        try:
            with tempfile.TemporaryDirectory(prefix="bench-timeline-") as results:
                benchmark = self._task(run, Path(results))
                timings, size = self._render(run, repeat)
        finally:
            if benchmark is not None:
                benchmark.delete()
            Run.objects.filter(pk=run.pk).delete()
        self.stdout.write(
            f"bench_timeline: render_ms_median={statistics.median(timings):.2f} "
            f"render_ms_max={max(timings):.2f} steps={STEPS} entries={size} "
            f"target_ms={TARGET_MS:g}"
        )

    def _task(self, run: Run, results: Path) -> BenchmarkRun:
        root = environment_root(run)
        for n in range(STEPS):  # the world moves on; the agent looks every 6 s
            at = n * TASK_S / STEPS
            lifecycle.advance(run, at)
            record_view(run, f"{root}/?folder=inbox", at=at)
        lifecycle.advance(run, TASK_S)
        lifecycle.contact(run, method="POST", message="Kevin Lee has written to you.")
        folder = results / "timeline" / run.environment / run.scenario_id
        folder.mkdir(parents=True)
        write_transcript(folder, root)
        benchmark = BenchmarkRun.objects.create(
            name=f"bench-timeline-{run.pk}", results_dir=str(results / "timeline")
        )
        TaskResult.objects.create(
            benchmark=benchmark,
            scenario_id=run.scenario_id,
            environment=run.environment,
            success=True,
            run=run,
        )
        return benchmark

    def _render(self, run: Run, repeat: int) -> tuple[list[float], int]:
        path = TIMELINE_PATH.format(run=run.pk)
        match = resolve(path)
        staff = User(username="bench-timeline", is_staff=True, is_superuser=True, is_active=True)
        timings, html = [], ""
        for attempt in range(repeat + 1):  # the first warms the templates up, untimed
            request = RequestFactory().get(path)
            request.user = staff
            began = time.perf_counter()
            response = match.func(request, *match.args, **match.kwargs)
            response.render()
            elapsed = (time.perf_counter() - began) * 1000
            if response.status_code != 200:
                raise CommandError(f"{path} answered {response.status_code}")
            html = response.content.decode()
            if attempt:
                timings.append(elapsed)
        return timings, html.count('<li id="tl-')
