"""The ticker fires timeline entries on time so open pages get pushed without a request.

One interface, two backends, both calling the same `fire_due`:
- `inprocess`: an asyncio loop inside the ASGI server (embedded default, no broker);
- `celery`: a beat heartbeat plus tasks scheduled at each run's next due time (events.tasks).

Either sleeps until the next due time (capped), never on a fixed coarse tick. Lazy catch-up
before every read keeps state exact even when the ticker is late or absent.
"""

from __future__ import annotations

import asyncio
import logging
import math
import threading

from asgiref.sync import sync_to_async
from django.conf import settings
from django.db import close_old_connections

from events.clock import wall_now
from events.models import Run, RunStatus
from events.scheduler import fire_due

log = logging.getLogger(__name__)

MAX_SLEEP_S = 1.0  # cap, so runs started by another process are noticed within a second


def next_wake(run: Run) -> float:
    """Wall time at which `run` next needs the ticker: its next entry or its timeline end."""
    due_sim = run.event_timeline_end if run.next_due_at is None else min(run.next_due_at, run.event_timeline_end)
    return run.started_at + due_sim / run.speed_factor


def live_runs():
    return Run.objects.filter(status=RunStatus.RUNNING_AUTO, closed_at__isnull=True).defer("scenario")


def tick(wall: float | None = None) -> float:
    """Fire every live run that is due; return how long the caller may sleep."""
    wall = wall_now() if wall is None else wall
    wake = math.inf
    for run in live_runs():
        if run.started_at is None:
            continue
        at = next_wake(run)
        if at <= wall:
            fire_due(run, fresh=True)
            if run.status == RunStatus.RUNNING_AUTO:
                at = next_wake(run)
        wake = min(wake, at)
    return max(0.0, min(MAX_SLEEP_S, wake - wall_now()))


class InProcessTicker:
    """An asyncio loop calling `tick`; `wake()` cuts a sleep short when a clock starts."""

    def __init__(self) -> None:
        self._loop: asyncio.AbstractEventLoop | None = None
        self._wakeup: asyncio.Event | None = None
        self._task: asyncio.Task | None = None

    @property
    def running(self) -> bool:
        return self._task is not None and not self._task.done()

    def ensure_started(self) -> None:
        """Start the loop on the running event loop (idempotent)."""
        if self.running:
            return
        self._loop = asyncio.get_running_loop()
        self._wakeup = asyncio.Event()
        self._task = self._loop.create_task(self._run_forever(), name="sentinel-ticker")

    def wake(self) -> None:
        if self._loop is not None and self._wakeup is not None and not self._loop.is_closed():
            self._loop.call_soon_threadsafe(self._wakeup.set)

    async def stop(self) -> None:
        if self._task is not None:
            self._task.cancel()
            try:
                await self._task
            except asyncio.CancelledError:
                pass
        self._task = None

    async def _run_forever(self) -> None:
        step = sync_to_async(self._tick_once, thread_sensitive=False)
        while True:
            try:
                delay = await step()
            except asyncio.CancelledError:
                raise
            except Exception:  # keep ticking: one bad run must not stop every other clock
                log.exception("ticker step failed")
                delay = MAX_SLEEP_S
            self._wakeup.clear()
            try:
                await asyncio.wait_for(self._wakeup.wait(), timeout=delay)
            except TimeoutError:
                pass

    @staticmethod
    def _tick_once() -> float:
        close_old_connections()
        return tick()


ticker = InProcessTicker()


def run_ticker_in_thread(stop: threading.Event) -> threading.Thread:
    """Run the in-process ticker on its own event loop in a thread (tests, bench commands)."""

    def target() -> None:
        loop = asyncio.new_event_loop()

        async def main() -> None:
            ticker.ensure_started()
            while not stop.is_set():
                await asyncio.sleep(0.05)
            await ticker.stop()

        loop.run_until_complete(main())
        loop.close()

    thread = threading.Thread(target=target, name="sentinel-ticker", daemon=True)
    thread.start()
    return thread


def notify_clock_started(run: Run) -> None:
    """Tell the configured ticker that a live clock started, so it does not wait for a cap."""
    if settings.SENTINEL_TICKER == "inprocess":
        ticker.wake()
    elif settings.SENTINEL_TICKER == "celery":
        from events.tasks import fire_run

        fire_run.delay(run.pk)
