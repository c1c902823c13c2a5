"""Threads are lent in fair turns: one run's flood of requests cannot starve another run's pages
(finding: with one client holding 24 requests in flight, another run's page went from ≈8 ms to
150–950 ms)."""

from __future__ import annotations

import asyncio
from concurrent.futures import ThreadPoolExecutor

from sentinel_site.http_handler import Turns, tenant_of


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


def test_a_runs_pages_are_its_token_and_everything_else_its_client():
    assert tenant_of({"path": "/r/abc123/micromail/", "client": ("10.0.0.1", 5)}) == "abc123"
    assert tenant_of({"path": "/api/runs/", "client": ("10.0.0.1", 5)}) == "10.0.0.1"
