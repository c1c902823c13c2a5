"""The ticker fires timeline entries on time so open pages get pushed without a request.

One interface, two backends, both calling the same `fire_due`:
- `inprocess`: an asyncio loop inside the ASGI server (embedded default, no broker);
- `celery`: a beat heartbeat plus tasks scheduled at each run's next due time (events.tasks).

Either sleeps until the next due time (capped), never on a fixed coarse tick. Lazy catch-up
before every read keeps state exact even when the ticker is late or absent.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import math
import threading

from asgiref.sync import sync_to_async
from django.conf import settings
from django.db import close_old_connections

from events.clock import wall_now
from events.models import Run, RunStatus
from events.retention import purge_if_due
from events.scheduler import TICK_BATCH, fire_due, fired_through, live_runs, next_wake

log = logging.getLogger(__name__)

MAX_SLEEP_S = 1.0  # cap, so runs started by another process are noticed within a second


class Schedule:
    """The ticker's in-memory view of live runs: when each next needs firing.

    Rebuilt from the database at most every MAX_SLEEP_S (or when woken), so a tick costs no
    query for runs that are not due. Positions are only hints: fire_due re-reads the run and the
    unique index keeps firing exactly-once whoever else fires.
    """

    def __init__(self, refresh_s: float = MAX_SLEEP_S) -> None:
        self.refresh_s = refresh_s  # a ticker nobody wakes (its own process) refreshes sooner
        self.runs: dict[int, Run] = {}
        self.next_index: dict[int, int] = {}
        self.refreshed_at = -math.inf

    def refresh(self, wall: float) -> None:
        purge_if_due()  # once a day: old runs go (events.retention)
        current = {run.pk: run for run in live_runs()}
        for pk in list(self.runs):
            if pk not in current:
                del self.runs[pk]
                self.next_index.pop(pk, None)
        for pk, run in current.items():
            if pk not in self.runs:
                self.next_index[pk] = fired_through(run) + 1
            self.runs[pk] = run
        self.refreshed_at = wall

    def tick(self, wall: float | None = None) -> float:
        """Fire every due run; return how long the caller may sleep."""
        wall = wall_now() if wall is None else wall
        if wall - self.refreshed_at >= self.refresh_s:
            self.refresh(wall)
        wake = self.refreshed_at + self.refresh_s
        for pk, run in list(self.runs.items()):
            at = next_wake(run, self.next_index[pk])
            if at is not None and at <= wall:
                result = fire_due(run, next_index=self.next_index[pk], limit=TICK_BATCH)
                self.next_index[pk] = result.next_index
                if run.status != RunStatus.RUNNING_AUTO or run.closed_at is not None:
                    del self.runs[pk]
                    continue
                at = next_wake(run, result.next_index)
            if at is not None:
                wake = min(wake, at)
        return max(0.0, min(self.refresh_s, wake - wall_now()))


def tick(wall: float | None = None) -> float:
    """One stateless pass (rebuilds the schedule): for callers without a long-lived ticker."""
    return Schedule().tick(wall)


class InProcessTicker:
    """An asyncio loop calling `tick`; `wake()` cuts a sleep short when a clock starts."""

    def __init__(self, refresh_s: float = MAX_SLEEP_S) -> None:
        self.refresh_s = refresh_s
        self.schedule = Schedule(refresh_s)
        self._loop: asyncio.AbstractEventLoop | None = None
        self._wakeup: asyncio.Event | None = None
        self._task: asyncio.Task | None = None

    @property
    def running(self) -> bool:
        return self._task is not None and not self._task.done()

    def ensure_started(self) -> None:
        """Start the loop on the running event loop (idempotent)."""
        loop = asyncio.get_running_loop()
        if self.running and self._loop is loop:
            return
        self._loop = loop  # a new event loop (tests, a restarted server): start afresh on it
        self._wakeup = asyncio.Event()
        self._task = self._loop.create_task(self._run_forever(), name="sentinel-ticker")

    def wake(self) -> None:
        self.schedule.refreshed_at = -math.inf  # a clock started: re-read the live runs
        if self._loop is not None and self._wakeup is not None and not self._loop.is_closed():
            self._loop.call_soon_threadsafe(self._wakeup.set)

    async def stop(self) -> None:
        if self._task is not None:
            self._task.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await self._task
        self._task = None

    async def _run_forever(self) -> None:
        step = sync_to_async(self._tick_once, thread_sensitive=False)
        self.schedule = Schedule(self.refresh_s)
        while True:
            try:
                delay = await step()
            except asyncio.CancelledError:
                raise
            except Exception:  # keep ticking: one bad run must not stop every other clock
                log.exception("ticker step failed")
                delay = MAX_SLEEP_S
            wakeup = self._wakeup  # the latest ensure_started()'s (read each time, as wake() does)
            assert wakeup is not None, "ensure_started() sets it before it starts this loop"
            wakeup.clear()
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(wakeup.wait(), timeout=delay)

    def _tick_once(self) -> float:
        close_old_connections()
        return self.schedule.tick()


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

        try:
            fire_run.delay(run.pk)
        except Exception:  # broker unreachable: the clock has started all the same
            log.warning("could not wake the Celery ticker; its heartbeat will find run %s", run.pk)
