"""The websocket behind live pages: `/r/<token>/live`, one socket per open page.

Protocol (JSON text frames):
- client → server, on open and after every in-page navigation:
  `{"url": "/r/<token>/micromail/?folder=inbox", "seq": <log position the page shows>,
    "due": <simulated second its content next changes with the clock, or null>}`
- server → client, whenever the run's log grows by a scenario or action event, or the clock
  reaches the page's `due`, and what the regions show (text, clock, pictures: apps.kit.visible)
  reads differently from what this socket last sent:
  `{"type": "regions", "url": …, "seq": N, "next_change": <the new due, or null>,
    "html": "<nav id=… data-live hx-swap-oob=\"true\">…"}`
  (the log grew but nothing shown changed: the same frame with `"html": ""`, which moves the
  page's log position and due time and swaps nothing),
  and `{"type": "error", "detail": …}` for a URL that is not one of this run's pages.

Clock-driven pushes: after each push (and on subscribing) the socket sets one timer for the wall
time at which the page's `next_change` comes on the run's clock, when the clock is running; a
clock moved by hand (`/advance`, start, a fast-forward skip) is broadcast as `run.clock_moved`
and re-checked at once. At most one clock-driven push per wall second per socket while time
passes, whatever the speed factor; a jump is pushed at once.

The socket joins the channel group of its run only, so one run's events never reach another
run's pages.
"""

from __future__ import annotations

import asyncio
import logging
import math

from channels.db import database_sync_to_async
from channels.generic.websocket import AsyncJsonWebsocketConsumer

from apps.kit import live
from events.clock import sim_now, wall_due, wall_now
from events.models import RunStatus

log = logging.getLogger(__name__)

CLOCK_PUSH_INTERVAL_S = 1.0  # at most one clock-driven push per wall second
# A timer fires this long after its due time, so the run's clock has surely reached it (the wall
# → simulated conversion rounds) and the re-render shows the change.
DUE_MARGIN_S = 0.02


def _finite(value: object) -> float | None:
    """A client's `due` as simulated seconds, or None when it is not a finite number."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        return None
    try:
        number = float(value)
    except OverflowError:  # an integer beyond any float
        return None
    return number if math.isfinite(number) else None


# Readings of a run's clock in flight on this event loop: every socket on a page wakes at the
# same due time, and one read taken after they woke serves them all (50 sockets made 50 reads).
_readings: dict[int, asyncio.Task] = {}


async def shared_clock_reading(run_id: int) -> dict | None:
    """The run's clock, fresh from the database: joins a read already under way, else starts one."""
    task = _readings.get(run_id)
    if task is None:
        task = asyncio.ensure_future(database_sync_to_async(live.clock_reading)(run_id))
        _readings[run_id] = task
        task.add_done_callback(lambda _: _readings.pop(run_id, None))
    return await asyncio.shield(task)  # one socket closing does not cancel the others' read


class RunLiveConsumer(AsyncJsonWebsocketConsumer):
    async def connect(self) -> None:
        token = self.scope["url_route"]["kwargs"]["token"]
        self.run = await database_sync_to_async(live.open_run)(token)
        if self.run is None:
            await self.close(code=4404)
            return
        headers = dict(self.scope.get("headers") or [])
        self.host = headers.get(b"host", b"testserver").decode("latin-1")
        self.url: str | None = None
        self.seen = 0
        self.clock = self.run  # the run's clock as last read (status, start, simulated time)
        self.next_change: float | None = None  # when the page shown next changes with the clock
        # What the regions last sent look like (apps.kit.visible): a push that would not change
        # what a person sees is not sent — whatever moved in the log or on the clock.
        self.sent: str | None = None
        self.clock_pushed_at = float("-inf")
        self.timer: asyncio.TimerHandle | None = None
        self.due_task: asyncio.Task | None = None
        self.group = live.group_name(self.run.pk)
        await self.channel_layer.group_add(self.group, self.channel_name)
        await self.accept()

    async def disconnect(self, code) -> None:
        if getattr(self, "group", None):
            self.disarm()
            if self.due_task is not None:
                self.due_task.cancel()
            await self.channel_layer.group_discard(self.group, self.channel_name)

    async def receive(self, text_data=None, bytes_data=None, **kwargs) -> None:
        try:
            content = await self.decode_json(text_data) if text_data else None
        except ValueError:  # not JSON (or nested beyond the parser): say so, keep the socket
            content = None
        if content is None:
            await self.send_json({"type": "error", "detail": "send a JSON object {url, seq, due}"})
            return
        await self.receive_json(content, **kwargs)

    async def receive_json(self, content, **kwargs) -> None:
        url = content.get("url") if isinstance(content, dict) else None
        try:
            live.page_path_for(self.run, url)
        except live.NotLive as exc:
            await self.send_json({"type": "error", "detail": str(exc)})
            return
        seq, due = content.get("seq"), content.get("due")
        self.disarm()
        self.url, self.sent = url, None
        self.seen = seq if isinstance(seq, int) and seq >= 0 else 0
        self.next_change = _finite(due)
        # An event may have fired, or the clock moved, between the page's render and now.
        latest, reading = await database_sync_to_async(live.subscription)(self.run.pk)
        if reading is not None:
            self.clock = live.with_clock(self.run, reading)
        if latest > self.seen:
            await self.push(latest)
        else:
            await self.note_shown(str(url))  # page_path_for checked it is a URL of this run
            self.arm()

    async def note_shown(self, url: str) -> None:
        """What the page looks like as the client has it — the same log position, the same
        clock window — so that a first push that would change nothing is not sent either."""
        now = sim_now(self.clock, wall_now())
        if self.next_change is not None and now >= self.next_change:
            return  # the clock moved on since the page was rendered: it shows an older window
        try:
            update = await live.shared_update(self.run, url, self.seen, now, self.host)
        except Exception:  # a page that cannot be rendered live is pushed nothing anyway
            return
        if update.seq <= self.seen and url == self.url:
            self.sent = update.looks

    async def run_log_grew(self, message: dict) -> None:
        if self.url is not None and message["seq"] > self.seen:
            await self.push(message["seq"])

    async def run_clock_moved(self, message: dict) -> None:
        self.clock = live.with_clock(self.run, message["clock"])
        # A jump is a request's doing, not time passing at speed: pushed at once, not held back
        # by the clock-push rate limit (a fast-forward agent reads the page right after).
        self.clock_pushed_at = float("-inf")
        self.arm()  # re-check the due time now: it may have come, or a timer may be needed

    async def push(self, seq: int, *, clock_driven: bool = False) -> None:
        url = self.url
        assert url is not None, "a push before any page subscribed"  # receive_json sets it first
        now = sim_now(self.clock, wall_now())
        try:
            update = await live.shared_update(self.run, url, seq, now, self.host)
        except live.NotLive as exc:
            # e.g. the open item was purged meanwhile: the page stays as it is until navigated.
            log.info("no live update for %s: %s", url, exc)
            self.seen, self.next_change = max(self.seen, seq), None
            return
        except Exception:  # a page that fails to render must not close every push after it
            log.exception("live render of %s failed", url)
            self.seen, self.next_change = max(self.seen, seq), None
            return
        if url != self.url:
            return  # the page navigated meanwhile; its new URL brought its own push
        self.seen = max(self.seen, update.seq, seq)
        self.next_change = update.next_change
        if update.looks != self.sent:
            self.sent = update.looks
            await self.send(text_data=update.text)
        elif not clock_driven:
            # The log grew but the page reads the same: only its position moves (a
            # fast-forward agent reads it to know the page caught up), nothing is swapped.
            await self.send_json(update.position())
        self.arm()

    # -- the clock timer ------------------------------------------------------------------------

    def disarm(self) -> None:
        if self.timer is not None:
            self.timer.cancel()
            self.timer = None

    def arm(self) -> None:
        """Set the one timer for the page's next clock-driven change, if the clock brings it."""
        self.disarm()
        if self.url is None or self.next_change is None:
            return
        wall = wall_now()
        due: float | None
        if sim_now(self.clock, wall) >= self.next_change:
            due = wall  # already there (a clock moved by hand, a late subscription)
        elif self.clock.status == RunStatus.RUNNING_AUTO:
            if self.next_change > self.clock.event_timeline_end:
                return  # the clock stops at the timeline's end, before the change
            due = wall_due(self.clock, self.next_change)
        else:
            return  # a stopped clock changes nothing until it is moved (run.clock_moved)
        if due is None:
            return
        due = max(due + DUE_MARGIN_S, self.clock_pushed_at + CLOCK_PUSH_INTERVAL_S)
        self.timer = asyncio.get_running_loop().call_later(max(0.0, due - wall), self.on_due)

    def on_due(self) -> None:
        self.timer = None
        if self.due_task is None or self.due_task.done():
            self.due_task = asyncio.ensure_future(self.clock_due())
        # else: the previous one is still rendering and re-arms when done

    async def clock_due(self) -> None:
        reading = await shared_clock_reading(self.run.pk)
        if reading is None or self.next_change is None:
            return
        self.clock = live.with_clock(self.run, reading)  # a fresh read: it may have stopped
        wall = wall_now()
        if sim_now(self.clock, wall) < self.next_change:
            self.arm()  # completed, or moved meanwhile: not due after all
            return
        self.clock_pushed_at = wall
        await self.push(self.seen, clock_driven=True)
