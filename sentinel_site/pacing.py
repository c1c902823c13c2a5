"""Fast-forward pacing: a few fast-forward agents awake at once; the others' waits are held
back while their clocks run, as a sleeping agent's would.

Why: a fast-forward agent never idles — its waits return at once — so ten of them on two cores
get a fifth of a core each, and everything an agent does between two waits (looking at the
page, asking its model, acting), which runs on the run's clock at its speed exactly as on a
live run, takes five times as many simulated seconds as on a quiet machine. Verdicts and
reaction times then hang on the machine's load: two runs of the same twenty tasks at ten at a
time disagreed on a verdict and by 2.5 s of reaction, while at two at a time they matched the
live runs. Paced, only `places` agents work at once, each at a quiet machine's speed, and the
machine is no less busy.

How: a run is awake from when its clock starts or a wait of its is answered until its next
wait, its contact or its close (or for AWAKE_LAPSE_S: an agent that never waits, or went away
without its run being closed: two tasks in five of the benchmark end without a contact). A wait
that comes while `places` runs are awake is held — on the event loop, holding no thread — and
let go first come, first served when one of them goes to sleep, or at the latest just before
the moment it would have ended had the clock run on (the view works that moment out:
events.fastforward.natural_end). Its run's clock runs meanwhile, as while a live agent sleeps:
due entries fire on time and its pages are pushed; then the wait skips the rest of the way. So
a held wait lands where it would have, its log is the one it would have had, and nothing is
frozen: an agent that works while its wait is held spends its own clock's seconds, as ever.
A fast-forward run's first task-URL visit is held the same way (its clock starts when it is let
go). Nothing is held longer than MAX_HOLD_S.

A held request is asked of its view first (apps/control/pace.py): only the view knows whether
the run is a fast-forward one and until when its wait may be held; then it is sent again,
admitted, arriving anew — a wait's lengths ("5 seconds", "a change within 60") still count
from when it first arrived. Each server process paces the requests it serves, with
`SENTINEL_FAST_FORWARD_AWAKE` places (0, the default: no pacing — an agent that waits on a
remote model between two waits would hold a place it does not load the machine with).
"""

from __future__ import annotations

import asyncio
import time
import weakref
from collections import deque
from dataclasses import dataclass, field

from apps.control.pace import ADMITTED, ASK, ASKED_AT, HELD_HEADER, HOLD_HEADER, SCOPE_KEY
from apps.kit.pages import ARRIVAL
from events.models import Run
from events.notifications import run_closed_signal
from sentinel_site.urls import RUN_PATHS

AWAKE_LAPSE_S = 10.0  # an awake run that has not waited, contacted or closed since counts no more
# No request is held longer, whatever is awake: an agent's HTTP client would give up (30 s, the
# reference agents'), and a held wait is a sleep whose clock runs — nothing is lost by it.
MAX_HOLD_S = 10.0
EARLY_S = 0.2  # a wait is let go this long before it would have ended (the time to answer it)

WAIT, START, CONTACT = "wait", "start", "contact"
_PACED = {(WAIT, "POST"), (START, "GET"), (CONTACT, "GET"), (CONTACT, "POST")}
_HOLD = HOLD_HEADER.lower().encode()
_HELD = HELD_HEADER.lower().encode()
_ANSWERED = object()  # the view answered the request itself: nothing to hold

_pacers: weakref.WeakSet[Pacer] = weakref.WeakSet()


def paced_request(scope) -> tuple[str, str] | None:
    """(run token, wait | start | contact) of a request the pacer looks at; None otherwise."""
    path = scope.get("path", "")
    if not path.startswith(RUN_PATHS):
        return None
    token, _, rest = path[len(RUN_PATHS) :].partition("/")
    what = rest.rstrip("/")
    return (token, what) if (what, scope.get("method")) in _PACED else None


@dataclass(eq=False)
class Held:
    token: str
    turn: asyncio.Future
    timer: asyncio.TimerHandle | None = field(default=None)


class Pacer:
    """ASGI wrapper in front of the agents' request threads (see the module doc)."""

    def __init__(
        self,
        app,
        *,
        places: int,
        lapse_s: float = AWAKE_LAPSE_S,
        max_hold_s: float = MAX_HOLD_S,
        early_s: float = EARLY_S,
    ):
        if places < 0:
            raise ValueError(f"places must be ≥ 0 (0: no pacing), got {places}")
        self.app = app
        self.places = places
        self.lapse_s, self.max_hold_s, self.early_s = lapse_s, max_hold_s, early_s
        self.awake: dict[str, float] = {}  # run token → the loop time it woke at
        self.held: deque[Held] = deque()
        self._loop: asyncio.AbstractEventLoop | None = None
        self._lapse: asyncio.TimerHandle | None = None
        _pacers.add(self)

    async def __call__(self, scope, receive, send):
        paced = paced_request(scope) if self.places else None
        if paced is None:
            await self.app(scope, receive, send)
            return
        self._loop = asyncio.get_running_loop()
        token, what = paced
        if what != START:
            self._sleep(token)  # a run that waits or contacts is no longer awake
        if what == CONTACT:
            await self.app(scope, receive, send)
            return
        if what == WAIT and self._take_place(token):  # taken before it is answered
            await self._answer(token, scope, receive, send, held_ms=None)
            return
        body = Replayed(receive)
        until = await self._ask(scope, body.receive, send)
        if until is _ANSWERED:
            return
        latest = time.time() + self.max_hold_s
        held_ms = await self._hold(
            token, latest if until is None else min(until - self.early_s, latest)
        )
        # It arrives now (its clock ran meanwhile); what it asked for counts from when it asked.
        admitted = {**scope, ARRIVAL: time.time(), ASKED_AT: scope.get(ARRIVAL)}
        await self._answer(token, admitted, body.replay, send, held_ms)

    async def _ask(self, scope, receive, send):
        """The view's answer to "hold this back?": the wall time to let it go by at the latest
        (None: no such time), or _ANSWERED when it answered the client itself."""
        until: object = _ANSWERED

        async def asking(message):
            nonlocal until
            if message["type"] == "http.response.start":
                for name, value in message.get("headers", ()):
                    if name.lower() == _HOLD:
                        until = float(value) if value else None
                        return
            if until is _ANSWERED:
                await send(message)

        await self.app({**scope, SCOPE_KEY: ASK}, receive, asking)
        return until

    async def _hold(self, token: str, until: float) -> float:
        """Wait for the request's turn, which comes at wall time `until` at the latest; its run
        is awake once it comes. Milliseconds held."""
        loop = self._loop
        assert loop is not None
        began = loop.time()
        if self._take_place(token):
            return 0.0
        held = Held(token, loop.create_future())
        held.timer = loop.call_later(max(0.0, until - time.time()), self._let_go, held)
        self.held.append(held)
        self._watch_lapses()
        try:
            await held.turn
        except asyncio.CancelledError:  # the client went away
            if held.turn.done() and not held.turn.cancelled():
                self._sleep(token)  # let go just as it went: pass its place on
            else:
                self._drop(held)
            raise
        return (loop.time() - began) * 1000

    async def _answer(self, token, scope, receive, send, held_ms: float | None) -> None:
        status = 500

        async def answering(message):
            nonlocal status
            if message["type"] == "http.response.start":
                status = message["status"]
                if held_ms is not None:
                    held = (_HELD, str(round(held_ms)).encode())
                    message = {**message, "headers": [*message.get("headers", ()), held]}
            await send(message)

        try:
            await self.app({**scope, SCOPE_KEY: ADMITTED}, receive, answering)
        finally:
            if status >= 400:
                self._sleep(token)  # refused (or failed): it did not wake

    def _take_place(self, token: str) -> bool:
        """Wake the run now if a place is free and nobody is held before it."""
        if self.held or not self._room():
            return False
        assert self._loop is not None
        self.awake[token] = self._loop.time()
        return True

    def _room(self) -> bool:
        assert self._loop is not None
        now = self._loop.time()
        for token, woke in list(self.awake.items()):
            if now - woke >= self.lapse_s:
                del self.awake[token]
        return len(self.awake) < self.places

    def _sleep(self, token: str) -> None:
        self.awake.pop(token, None)
        self._pump()

    def _pump(self) -> None:
        while self.held and self._room():
            self._let_go(self.held[0])
        self._watch_lapses()

    def _let_go(self, held: Held) -> None:
        self._drop(held)
        if not held.turn.done():
            assert self._loop is not None
            self.awake[held.token] = self._loop.time()
            held.turn.set_result(None)

    def _drop(self, held: Held) -> None:
        if held in self.held:
            self.held.remove(held)
        if held.timer is not None:
            held.timer.cancel()

    def _watch_lapses(self) -> None:
        """While requests are held, let the next one go when the oldest awake place lapses."""
        if self._lapse is not None:
            self._lapse.cancel()
            self._lapse = None
        if self.held and self.awake and self._loop is not None:
            self._lapse = self._loop.call_at(min(self.awake.values()) + self.lapse_s, self._pump)

    def forget(self) -> None:
        """Every run asleep, every held request let go (the test suite's kept server)."""
        self.awake.clear()
        while self.held:
            self._let_go(self.held[0])
        self._watch_lapses()

    def call(self, method, *args) -> None:
        """`method(*args)` on the pacer's event loop, from any thread (a loop gone: nothing)."""
        loop = self._loop
        if loop is not None and not loop.is_closed():
            loop.call_soon_threadsafe(method, *args)

    def shutdown(self) -> None:
        self.app.shutdown()


class Replayed:
    """A request's body as its first pass read it, for the second."""

    def __init__(self, receive):
        self._receive = receive
        self._messages: list[dict] = []

    async def receive(self):
        message = await self._receive()
        if message["type"] == "http.request":
            self._messages.append(message)
        return message

    async def replay(self):
        if self._messages:
            return self._messages.pop(0)
        return await self._receive()


def status() -> dict[str, list[str]]:
    """The run tokens awake and held by this process's pacers, now (read from any thread)."""
    pacers = list(_pacers)
    return {
        "awake": [token for pacer in pacers for token in list(pacer.awake)],
        "held": [held.token for pacer in pacers for held in list(pacer.held)],
    }


def forget_all() -> None:
    """Every pacer of this process forgets (from any thread: each on its own loop)."""
    for pacer in _pacing():
        pacer.call(pacer.forget)


def run_closed(token: str) -> None:
    """The run is closed: its place, if it held one, is free now rather than at its lapse (from
    any thread). An agent that ends without contacting — a no-op task watched to its end, a
    wait that timed out — sends no last wait; its harness closes the run as soon as it exits."""
    for pacer in _pacing():
        pacer.call(pacer._sleep, token)


def _pacing() -> list[Pacer]:
    return [pacer for pacer in list(_pacers) if pacer.places and pacer._loop is not None]


def _on_run_closed(sender, run_id: int, **details) -> None:
    if _pacing():  # the run's token only where a pacer may hold its place
        token = Run.objects.filter(pk=run_id).values_list("token", flat=True).first()
        if token is not None:
            run_closed(token)


run_closed_signal.connect(_on_run_closed, dispatch_uid="site.pacing.run_closed")
