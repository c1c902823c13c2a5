"""How Django's HTTP side runs under Daphne: one synchronous chain on one of a few kept threads.

Django's stock `ASGIHandler` is built for a mix of sync and async code, and on our pages —
every middleware and view synchronous — that generality was most of the cost of a request:

- It adapts the middleware chain for async, so a request bounced between the event loop and
  its worker thread several times (each bounce a cross-thread hand-off under the GIL), and it
  sends the request's signals in hops of their own. `SyncChainHandler` loads the chain
  synchronously instead and hands the whole request — `request_started`, middleware, view,
  and the response's close (`request_finished`) — to the worker thread in one hop: `/status`
  went from 2.5 to 1.6 ms median over a keep-alive connection.
- It enters a fresh `ThreadSensitiveContext` per request, for which asgiref starts a new
  thread and joins it when the request ends; database connections belong to threads, so each
  request also opened (and set up) a new connection. `RequestThreads` lends each request one
  of a fixed set of single-thread executors instead (asgiref's documented
  `ThreadSensitiveContext(executor=…)`), so threads, and with `CONN_MAX_AGE` their
  connections, outlive the request.

Django's guarantees are kept: a request's synchronous work all runs on one thread, no two
requests share a thread at once, request signals fire as before. When every thread is busy,
further requests wait on the event loop (no thread held) rather than spawning more, in one line
per run, served in turn (`Turns`): no run's flood of requests delays another run's pages, and
made-up run tokens share one line (`Tenants`).

Agents' pages have threads of their own (`Lanes`): an `/evaluate` (up to 2 s of eval_sql), an
admin dry run or a slow API call never holds a thread that an agent's page or contact waits for.
And every request is stamped with the wall time it arrived, before it waits for a thread, so a
contact counts from when the agent made it (apps/kit/pages.py `arrival_wall`).
"""

from __future__ import annotations

import asyncio
import time
from collections import OrderedDict, deque
from concurrent.futures import ThreadPoolExecutor

from asgiref.sync import ThreadSensitiveContext, sync_to_async
from django.conf import settings
from django.core import signals
from django.core.exceptions import RequestAborted
from django.core.handlers import base
from django.core.handlers.asgi import ASGIHandler, get_script_prefix
from django.db import connections
from django.http import FileResponse
from django.http.response import HttpResponseBase
from django.urls import set_script_prefix

from apps.kit.pages import ARRIVAL
from sentinel_site.pacing import Pacer
from sentinel_site.urls import RUN_PATHS

# Two: while one request waits on the database (SQLite's busy timeout, a PostgreSQL row lock),
# the other keeps pages moving. More only slice the GIL finer and stretch every request:
# bench_pages p95 went from 35 ms with two threads to 48 with three, 50 with four.
REQUEST_THREADS = 2
CONTROL_THREADS = 2  # the control API, evaluation, the admin: never on an agent's thread


class SyncChainHandler(ASGIHandler):
    """Django's ASGI handler with the middleware chain loaded (and run) synchronously, and a
    request's synchronous steps taken in one hop to its thread.

    Django's `handle` hops to the thread three times — the `request_started` signal, the chain
    and view, the response's `close` (the `request_finished` signal) — and runs a second task
    that listens for the client going away, to cancel a view that a thread-bound view ignores
    anyway. Each hop wakes a thread and then the event loop: on a `/status` that was a third
    of the request. Here all three steps run in one hop (a streaming response is still closed
    after it is sent, as its content is produced while sending); a client that goes away is
    Daphne's to tidy up, as for any finished application."""

    def __init__(self):
        base.BaseHandler.__init__(self)  # not ASGIHandler.__init__: that loads it for async
        self.load_middleware(is_async=False)

    async def handle(self, scope, receive, send):
        try:
            body_file = await self.read_body(receive)
        except RequestAborted:
            return
        try:
            set_script_prefix(get_script_prefix(scope))
            response = await sync_to_async(self.respond, thread_sensitive=True)(scope, body_file)
            await self.send_response(response, send)
            if response.streaming:
                await sync_to_async(response.close, thread_sensitive=True)()
        finally:
            body_file.close()

    def respond(self, scope, body_file) -> HttpResponseBase:
        """The response, on the request's thread: signalled started, answered, and — when its
        content is already whole — closed (signalled finished)."""
        signals.request_started.send(sender=self.__class__, scope=scope)
        request, response = self.create_request(scope, body_file)
        if request is not None:
            response = self.get_response(request)
            response._handler_class = self.__class__
            if isinstance(response, FileResponse):
                response.block_size = self.chunk_size  # as ASGIHandler: Daphne chunks for us
        if not response.streaming:
            response.close()
        return response


class Turns:
    """Lends a fixed set of threads to waiting requests fairly: one waiting line per tenant (a
    run's token), served in turn.

    One run's client with 24 requests in flight used to queue them ahead of everyone: another
    run's page then waited behind all 24 (≈8 ms became 150–950 ms). Now a free thread goes to the
    next tenant in rotation, so a page waits for at most one request of each other busy tenant,
    however many any one of them has queued. An idle thread is lent at once, last returned first
    (warm, with its database connection).
    """

    def __init__(self, executors: list[ThreadPoolExecutor]):
        self.idle = list(executors)
        self.lines: OrderedDict[object, deque[asyncio.Future]] = OrderedDict()

    async def take(self, tenant: object) -> ThreadPoolExecutor:
        if self.idle and not self.lines:
            return self.idle.pop()
        turn: asyncio.Future = asyncio.get_running_loop().create_future()
        self.lines.setdefault(tenant, deque()).append(turn)
        try:
            return await turn
        except asyncio.CancelledError:  # the client went away while it waited
            if turn.done() and not turn.cancelled():
                self.give_back(turn.result())  # lent just as it was cancelled: pass it on
            else:
                line = self.lines.get(tenant)
                if line is not None and turn in line:
                    line.remove(turn)
                    if not line:
                        del self.lines[tenant]
            raise

    def give_back(self, executor: ThreadPoolExecutor) -> None:
        while self.lines:
            tenant, line = next(iter(self.lines.items()))
            turn = line.popleft()
            if line:
                self.lines.move_to_end(tenant)  # its next request waits for everyone else's turn
            else:
                del self.lines[tenant]
            if not turn.done():
                turn.set_result(executor)
                return
        self.idle.append(executor)


PROVEN_TOKENS = 4096  # tokens of runs this process has answered pages of, the latest kept


class Tenants:
    """Whose turn a request takes: a run's pages their run's, anything else its client's.

    A token takes a turn of its own once a request under it has been answered with a page, not
    an error: a made-up token is no run, and a client that sprayed made-up tokens got a turn per
    token (a thousand connections, a thousand turns against each real run's one), so a real run's
    page waited for all of them. Until a token is proven, its requests share one line with every
    other unproven token from the same client address: a run's first page may wait there, its
    later ones take their own turns. Used on the event loop only."""

    def __init__(self, size: int = PROVEN_TOKENS):
        self.size = size
        self.proven: OrderedDict[str, None] = OrderedDict()

    def of(self, scope) -> object:
        client = (scope.get("client") or ("", 0))[0]
        token = run_token(scope)
        if token is None:
            return client
        if token in self.proven:
            self.proven.move_to_end(token)
            return token
        return ("unproven tokens from", client)

    def answered(self, scope, status: int) -> None:
        """A request was answered with `status`: a page proves its run's token."""
        token = run_token(scope)
        if token is None or status >= 400 or token in self.proven:
            return
        self.proven[token] = None
        if len(self.proven) > self.size:
            self.proven.popitem(last=False)


def run_token(scope) -> str | None:
    """The run token a request's path is under, if any."""
    path = scope.get("path", "")
    if not path.startswith(RUN_PATHS):
        return None
    return path[len(RUN_PATHS) :].split("/", 1)[0] or None


class RequestThreads:
    """ASGI wrapper: each request borrows one of `size` long-lived worker threads, in fair turns."""

    def __init__(self, app, *, size: int = REQUEST_THREADS, name: str = "request"):
        if size < 1:
            raise ValueError(f"RequestThreads needs at least one thread, got {size}")
        self.app = app
        self.size = size
        self.name = name
        # Created on first use: the waiting lines' futures belong to the serving event loop.
        self._turns: Turns | None = None
        self.tenants = Tenants()

    def turns(self) -> Turns:
        if self._turns is None:
            self._turns = Turns(
                [
                    ThreadPoolExecutor(max_workers=1, thread_name_prefix=f"{self.name}-{index}")
                    for index in range(self.size)
                ]
            )
        return self._turns

    def shutdown(self) -> None:
        """Close each thread's database connections and stop the threads (no request running)."""
        if self._turns is None:
            return
        for executor in self._turns.idle:
            executor.submit(connections.close_all).result()
            executor.shutdown()
        self._turns = None

    async def __call__(self, scope, receive, send):
        turns = self.turns()
        executor = await turns.take(self.tenants.of(scope))

        async def answer(message):
            if message["type"] == "http.response.start":
                self.tenants.answered(scope, message["status"])
            await send(message)

        try:
            async with ThreadSensitiveContext(executor=executor):
                await self.app(scope, receive, answer)
        finally:
            turns.give_back(executor)


class Lanes:
    """ASGI router: agents' pages on their own threads, everything else on others; each request
    stamped with its arrival time first."""

    def __init__(self, agent, control):
        self.agent, self.control = agent, control

    async def __call__(self, scope, receive, send):
        scope = {**scope, ARRIVAL: time.time()}
        if scope.get("path", "").startswith(RUN_PATHS):
            await self.agent(scope, receive, send)
        else:
            await self.control(scope, receive, send)

    def shutdown(self) -> None:
        self.agent.shutdown()
        self.control.shutdown()


def django_http_application():
    """The HTTP application Daphne serves (Django must already be set up)."""
    handler = SyncChainHandler()
    return Lanes(
        Pacer(
            RequestThreads(handler, size=REQUEST_THREADS, name="agent"),
            places=settings.SENTINEL_FAST_FORWARD_AWAKE,
        ),
        RequestThreads(handler, size=CONTROL_THREADS, name="control"),
    )
