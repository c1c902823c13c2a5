"""Fast-forward pacing (sentinel_site/pacing.py), on the event loop, in front of an ASGI app that
answers as the agent views do (apps/control/agent.py): a fast-forward run's wait or first
visit, asked, answers "hold me until …"; admitted, it is answered. The same views behind a real
Daphne: tests/live/test_pacing_server.py."""

from __future__ import annotations

import asyncio
import json
import threading
import time

import pytest

from apps.control.pace import ADMITTED, ASK, HOLD_HEADER, SCOPE_KEY
from apps.kit.pages import ARRIVAL
from sentinel_site.pacing import Pacer, paced_request, run_closed

CEILING_S = 30  # a ceiling, not a wait: every awaited answer comes as soon as its turn does


class AgentViews:
    """ASGI app: the runs' answers, and every pass it served (path, what the pacer asked)."""

    def __init__(self, *, live: tuple[str, ...] = (), ends: dict[str, float] | None = None):
        self.live = live  # tokens of runs on live clocks: their visits are never held
        self.ends = ends or {}  # token → the wall time its wait would end at
        self.passes: list[tuple[str, str | None]] = []
        self.refuse: set[str] = set()  # tokens whose admitted wait is refused (409)

    async def __call__(self, scope, receive, send):
        body = b""
        while True:
            message = await receive()
            body += message.get("body", b"")
            if not message.get("more_body"):
                break
        token, _, what = scope["path"].removeprefix("/r/").partition("/")
        self.passes.append((scope["path"], scope.get(SCOPE_KEY)))
        if scope.get(SCOPE_KEY) == ASK and token not in self.live and what != "contact":
            until = self.ends.get(token)
            header = (HOLD_HEADER.encode(), b"" if until is None else repr(until).encode())
            await send({"type": "http.response.start", "status": 202, "headers": [header]})
            await send({"type": "http.response.body", "body": b""})
            return
        status = 409 if token in self.refuse and what == "wait" else 200
        answer = {"body": body.decode(), "arrived": scope.get(ARRIVAL)}
        await send({"type": "http.response.start", "status": status, "headers": []})
        await send({"type": "http.response.body", "body": json.dumps(answer).encode()})


class Client:
    """One request through the pacer: its status, headers and answer once it is answered."""

    def __init__(self, pacer: Pacer, method: str, path: str, body: bytes = b""):
        self.start: dict | None = None
        self.answer = b""
        self.answered_at: float | None = None
        scope = {"type": "http", "method": method, "path": path, ARRIVAL: time.time()}
        self.task = asyncio.create_task(pacer(scope, self._receive(body), self._send))

    def _receive(self, body: bytes):
        sent = False

        async def receive():
            nonlocal sent
            if not sent:
                sent = True
                return {"type": "http.request", "body": body, "more_body": False}
            await asyncio.Event().wait()  # the client stays connected

        return receive

    async def _send(self, message):
        if message["type"] == "http.response.start":
            self.start = message
        else:
            self.answer += message.get("body", b"")
            self.answered_at = time.monotonic()

    async def answered(self) -> Client:
        await asyncio.wait_for(asyncio.shield(self.task), CEILING_S)
        return self

    @property
    def status(self) -> int:
        assert self.start is not None
        return self.start["status"]

    @property
    def held_ms(self) -> float | None:
        for name, value in self.start["headers"] if self.start else ():
            if name == b"x-sentinel-held-ms":
                return float(value)
        return None


async def settled() -> None:
    """Let every task run until it blocks (requests arrive and join the line)."""
    for _ in range(20):
        await asyncio.sleep(0)


def play(scenario, **pacer):
    async def main():
        views = AgentViews(**pacer.pop("views", {}))
        return await scenario(Pacer(views, **pacer), views)

    return asyncio.run(main())


def test_a_start_while_every_place_is_taken_is_held_until_an_awake_run_waits():
    async def scenario(pacer, views):
        a = await Client(pacer, "GET", "/r/a/start").answered()
        assert (a.status, a.held_ms) == (200, 0)
        b = Client(pacer, "GET", "/r/b/start")
        await settled()
        assert not b.task.done() and list(pacer.awake) == ["a"]
        a_waits = Client(pacer, "POST", "/r/a/wait", b'{"seconds": 30}')
        await b.answered()
        assert b.status == 200 and b.held_ms is not None and b.held_ms >= 0
        assert list(pacer.awake) == ["b"]  # a went to sleep: b has its place …
        await settled()
        assert not a_waits.task.done()  # … and a's wait is held behind b, with no end known
        Client(pacer, "POST", "/r/b/contact")  # b is done
        await a_waits.answered()
        assert a_waits.status == 200 and list(pacer.awake) == ["a"]

    play(scenario, places=1)


def test_a_held_wait_is_let_go_just_before_it_would_have_ended_though_nobody_slept():
    ends = {"b": time.time() + 0.6}

    async def scenario(pacer, views):
        await Client(pacer, "GET", "/r/a/start").answered()
        b = await Client(pacer, "POST", "/r/b/wait", b'{"to": 42}').answered()
        assert b.status == 200
        assert time.time() >= ends["b"] - pacer.early_s  # not before: no place came free
        assert set(pacer.awake) == {"a", "b"}  # over the places: a wait never lands late

    play(scenario, places=1, views={"ends": ends})


def test_nothing_is_held_longer_than_the_longest_hold():
    ends = {"b": time.time() + 600}  # a long sleep: its natural end is far away

    async def scenario(pacer, views):
        await Client(pacer, "GET", "/r/a/start").answered()
        since = time.monotonic()
        b = await Client(pacer, "POST", "/r/b/wait", b'{"seconds": 600}').answered()
        c = await Client(pacer, "GET", "/r/c/start").answered()
        assert (b.status, c.status) == (200, 200)
        assert time.monotonic() - since >= 0.3 * 0.9  # no sooner: a and then b stayed awake

    play(scenario, places=1, max_hold_s=0.3, views={"ends": ends})


def test_a_wait_admitted_after_being_held_arrives_anew_with_its_own_body():
    async def scenario(pacer, views):
        await Client(pacer, "GET", "/r/a/start").answered()
        held = Client(pacer, "POST", "/r/b/wait", b'{"until": "change"}')
        await settled()
        asked_at = time.time()
        Client(pacer, "POST", "/r/a/wait", b"{}")
        answer = json.loads((await held.answered()).answer)
        assert answer["body"] == '{"until": "change"}'  # the body its first pass read
        assert answer["arrived"] >= asked_at  # the clock ran while it was held: it arrives now
        assert views.passes.count(("/r/b/wait", ASK)) == 1
        assert views.passes.count(("/r/b/wait", ADMITTED)) == 1

    play(scenario, places=1)


def test_held_requests_are_let_go_first_come_first_served():
    async def scenario(pacer, views):
        await Client(pacer, "GET", "/r/a/start").answered()
        line = [Client(pacer, "GET", f"/r/{token}/start") for token in "bcd"]
        await settled()
        for token in "abc":
            Client(pacer, "POST", f"/r/{token}/wait", b"{}")
            await settled()
        for client in line:
            await client.answered()
        order = sorted(line, key=lambda client: client.answered_at or 0)
        assert order == line

    play(scenario, places=1)


def test_an_awake_run_that_never_waits_gives_its_place_up_after_the_lapse():
    async def scenario(pacer, views):
        await Client(pacer, "GET", "/r/a/start").answered()
        since = time.monotonic()
        b = await Client(pacer, "GET", "/r/b/start").answered()
        assert b.status == 200 and time.monotonic() - since >= 0.3 * 0.9
        assert list(pacer.awake) == ["b"]

    play(scenario, places=1, lapse_s=0.3)


def test_a_live_runs_visit_passes_straight_through_and_takes_no_place():
    async def scenario(pacer, views):
        await Client(pacer, "GET", "/r/a/start").answered()
        live = await Client(pacer, "GET", "/r/l/start").answered()
        assert live.status == 200 and live.held_ms is None
        assert views.passes.count(("/r/l/start", ASK)) == 1  # answered on the asking pass
        assert list(pacer.awake) == ["a"]

    play(scenario, places=1, views={"live": ("l",)})


def test_a_refused_wait_takes_no_place():
    async def scenario(pacer, views):
        views.refuse.add("a")
        refused = await Client(pacer, "POST", "/r/a/wait", b"{}").answered()
        assert refused.status == 409 and pacer.awake == {}

    play(scenario, places=1)


def test_a_held_request_whose_client_goes_away_leaves_the_line():
    async def scenario(pacer, views):
        await Client(pacer, "GET", "/r/a/start").answered()
        gone = Client(pacer, "GET", "/r/b/start")
        stays = Client(pacer, "GET", "/r/c/start")
        await settled()
        gone.task.cancel()
        await settled()
        assert [held.token for held in pacer.held] == ["c"]
        Client(pacer, "POST", "/r/a/wait", b"{}")
        assert (await stays.answered()).status == 200
        assert "b" not in pacer.awake

    play(scenario, places=1)


def test_without_places_nothing_is_asked_or_held():
    async def scenario(pacer, views):
        for token in "abc":
            assert (await Client(pacer, "GET", f"/r/{token}/start").answered()).held_ms is None
        assert {asked for _, asked in views.passes} == {None}
        assert pacer.awake == {}

    play(scenario, places=0)


@pytest.mark.parametrize(
    ("method", "path", "paced"),
    [
        ("POST", "/r/tok/wait", ("tok", "wait")),
        ("GET", "/r/tok/start", ("tok", "start")),
        ("POST", "/r/tok/contact", ("tok", "contact")),
        ("GET", "/r/tok/wait", None),
        ("GET", "/r/tok/micromail/", None),
        ("POST", "/api/runs/", None),
    ],
)
def test_the_pacer_looks_at_waits_first_visits_and_contacts_only(method, path, paced):
    assert paced_request({"method": method, "path": path}) == paced


def test_a_closed_runs_place_goes_to_the_next_in_line_at_once():
    async def scenario(pacer, views):
        await Client(pacer, "GET", "/r/a/start").answered()
        b = Client(pacer, "GET", "/r/b/start")
        await settled()
        assert [held.token for held in pacer.held] == ["b"]
        # From another thread, as the close's notice comes (a request thread of the server).
        closer = threading.Thread(target=run_closed, args=("a",))
        closer.start()
        closer.join()
        assert (await b.answered()).status == 200
        assert list(pacer.awake) == ["b"]

    play(scenario, places=1, lapse_s=CEILING_S, max_hold_s=CEILING_S)
