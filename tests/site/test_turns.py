"""Threads are lent in fair turns: one run's flood of requests cannot starve another run's pages
(finding: with one client holding 24 requests in flight, another run's page went from ≈8 ms to
150–950 ms)."""

from __future__ import annotations

import asyncio
from concurrent.futures import ThreadPoolExecutor

from sentinel_site.http_handler import RequestThreads, Tenants, Turns


def served_order(requests: list[str], threads: int = 1) -> list[str]:
    """The order in which waiting requests (tenant names, in arrival order) get a thread, when
    every thread is busy as they arrive and each gives its thread back when it is served."""

    async def play() -> list[str]:
        executors = [ThreadPoolExecutor(max_workers=1) for _ in range(threads)]
        turns = Turns(executors)
        busy = [await turns.take("warm-up") for _ in range(threads)]
        served: list[str] = []

        async def request(tenant: str) -> None:
            executor = await turns.take(tenant)
            served.append(tenant)
            await asyncio.sleep(0)  # "work"
            turns.give_back(executor)

        waiting = []
        for tenant in requests:
            waiting.append(asyncio.create_task(request(tenant)))
            await asyncio.sleep(0)  # it arrives and joins its line
        for executor in busy:
            turns.give_back(executor)
        await asyncio.gather(*waiting)
        for executor in executors:
            executor.shutdown()
        return served

    return asyncio.run(play())


def test_a_late_tenant_is_served_next_not_after_a_flood():
    order = served_order(["flood"] * 20 + ["quiet"])
    assert order.index("quiet") == 1  # after the one flood request already first in turn


def test_tenants_take_turns_and_each_keeps_its_own_order():
    order = served_order(["a", "a", "a", "b", "b", "c"])
    assert order == ["a", "b", "c", "a", "b", "a"]


def test_an_idle_thread_is_lent_at_once():
    async def play():
        turns = Turns([ThreadPoolExecutor(max_workers=1)])
        executor = await asyncio.wait_for(turns.take("a"), timeout=1)
        turns.give_back(executor)
        assert turns.idle == [executor]
        executor.shutdown()

    asyncio.run(play())


def test_a_request_that_gives_up_waiting_leaves_its_line_and_loses_no_thread():
    async def play():
        executor = ThreadPoolExecutor(max_workers=1)
        turns = Turns([executor])
        held = await turns.take("a")
        gone = asyncio.create_task(turns.take("b"))
        await asyncio.sleep(0)
        gone.cancel()
        await asyncio.gather(gone, return_exceptions=True)
        assert "b" not in turns.lines
        turns.give_back(held)
        assert turns.idle == [executor]  # not lent to the request that left
        executor.shutdown()

    asyncio.run(play())


def scope(path: str, client: str = "10.0.0.1") -> dict:
    return {"type": "http", "path": path, "client": (client, 5)}


def test_a_runs_pages_take_their_runs_turn_once_a_page_proved_it_and_the_rest_their_clients():
    tenants = Tenants()
    page = scope("/r/abc123/micromail/")
    assert tenants.of(page) == ("unproven tokens from", "10.0.0.1")
    tenants.answered(page, 404)
    assert tenants.of(page) == ("unproven tokens from", "10.0.0.1")  # an error proves nothing
    tenants.answered(page, 200)
    assert tenants.of(page) == "abc123"
    assert tenants.of(scope("/api/runs/")) == "10.0.0.1"


def test_made_up_tokens_share_one_line_and_win_no_turns_over_a_real_run():
    """The finding: a client spraying made-up tokens got a turn per token, so a real run's
    page waited behind one request of each."""
    tenants = Tenants()
    tenants.answered(scope("/r/real/micromail/"), 200)
    flood = [tenants.of(scope(f"/r/fake{n}/micromail/", "10.6.6.6")) for n in range(20)]
    real = tenants.of(scope("/r/real/micromail/"))
    order = served_order([*flood, real])
    assert order.index(real) == 1  # after the one flood request already first in turn


def test_the_proven_tokens_kept_are_the_latest():
    tenants = Tenants(size=2)
    for token in ("a", "b", "c"):
        tenants.answered(scope(f"/r/{token}/"), 200)
    assert list(tenants.proven) == ["b", "c"]


def test_a_page_answered_through_the_threads_proves_its_token():
    async def app(scope, receive, send):
        status = 404 if "/nope/" in scope["path"] else 200
        await send({"type": "http.response.start", "status": status, "headers": []})
        await send({"type": "http.response.body", "body": b""})

    async def play() -> list[str]:
        threads = RequestThreads(app, size=1)
        sent: list[dict] = []

        async def send(message):
            sent.append(message)

        for path in ("/r/nope/micromail/", "/r/real/micromail/"):
            await threads(scope(path), None, send)
        threads.shutdown()
        assert [m.get("status") for m in sent if m["type"] == "http.response.start"] == [404, 200]
        return list(threads.tenants.proven)

    assert asyncio.run(play()) == ["real"]
