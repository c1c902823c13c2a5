"""Open-loop agents for `bench_scale`: each loads a page of its run on a fixed schedule.

An open-loop agent sends its next request when the schedule says, whether or not the last one
has come back — as a hundred independent agents would — so a slow server shows up as latency
instead of silently lowering the load (a closed loop's "coordinated omission"). Latency is
counted from the scheduled moment, so time spent queued anywhere (even in this process) counts.
"""

from __future__ import annotations

import asyncio
import itertools
import time
from dataclasses import dataclass, field

import httpx

REQUEST_TIMEOUT_S = 30.0


@dataclass(frozen=True)
class AgentPlan:
    """What one agent does: its run, the pages it cycles through, the actions it may take."""

    run_id: int
    task_path: str
    pages: list[str]
    actions_path: str
    actions: list[dict]  # {"action": name, "payload": {...}}, taken in turn


@dataclass
class LoadResult:
    page_ms: list[float] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)
    acknowledged: list[tuple[int, int]] = field(default_factory=list)  # (run id, seq)
    refused: int = 0  # actions the run's state refused (4xx): not acknowledged, not errors

    @property
    def requests(self) -> int:
        return len(self.page_ms)


class OpenLoop:
    """`agents` plans driven for `seconds` at `rate` pages/s each, an action every `act_every` s."""

    def __init__(
        self,
        base_url: str,
        plans: list[AgentPlan],
        *,
        rate: float,
        seconds: float,
        act_every: float,
    ):
        self.base_url, self.plans = base_url, plans
        self.rate, self.seconds, self.act_every = rate, seconds, act_every
        self.result = LoadResult()

    def run(self) -> LoadResult:
        asyncio.run(self._main())
        return self.result

    async def _main(self) -> None:
        limits = httpx.Limits(max_connections=4 * len(self.plans), max_keepalive_connections=None)
        async with httpx.AsyncClient(
            base_url=self.base_url, timeout=REQUEST_TIMEOUT_S, limits=limits
        ) as http:
            # Every agent opens its task URL first (that starts its run's clock), spread over a
            # second as agents launched together would be.
            spread = 1.0 / max(1, len(self.plans))
            await asyncio.gather(
                *(self._open(http, plan, i * spread) for i, plan in enumerate(self.plans))
            )
            began = time.monotonic()
            await asyncio.gather(
                *(self._agent(http, plan, began, i) for i, plan in enumerate(self.plans))
            )

    async def _open(self, http: httpx.AsyncClient, plan: AgentPlan, delay: float) -> None:
        await asyncio.sleep(delay)
        try:
            response = await http.get(plan.task_path, follow_redirects=True)
            if response.status_code != 200:
                self.result.errors.append(f"GET {plan.task_path}: HTTP {response.status_code}")
        except httpx.HTTPError as exc:
            self.result.errors.append(f"GET {plan.task_path}: {type(exc).__name__}: {exc}")

    async def _agent(self, http: httpx.AsyncClient, plan: AgentPlan, began: float, n: int):
        interval = 1.0 / self.rate
        offset = (n / len(self.plans)) * interval  # agents out of phase, as real ones are
        pages = itertools.cycle(plan.pages)
        actions = itertools.cycle(plan.actions) if plan.actions else None
        next_act = began + offset + self.act_every
        in_flight: set[asyncio.Task] = set()
        for k in itertools.count():
            scheduled = began + offset + k * interval
            if scheduled - began >= self.seconds:
                break
            await asyncio.sleep(max(0.0, scheduled - time.monotonic()))
            task = asyncio.create_task(self._page(http, next(pages), scheduled))
            in_flight.add(task)
            task.add_done_callback(in_flight.discard)
            if actions is not None and scheduled >= next_act:
                next_act += self.act_every
                task = asyncio.create_task(self._act(http, plan, next(actions)))
                in_flight.add(task)
                task.add_done_callback(in_flight.discard)
        if in_flight:
            await asyncio.gather(*in_flight)

    async def _page(self, http: httpx.AsyncClient, path: str, scheduled: float) -> None:
        try:
            response = await http.get(path)
        except httpx.HTTPError as exc:
            self.result.errors.append(f"GET {path}: {type(exc).__name__}: {exc}")
            return
        if response.status_code != 200:
            self.result.errors.append(f"GET {path}: HTTP {response.status_code}")
            return
        self.result.page_ms.append((time.monotonic() - scheduled) * 1000.0)

    async def _act(self, http: httpx.AsyncClient, plan: AgentPlan, step: dict) -> None:
        try:
            response = await http.post(plan.actions_path, json=step)
        except httpx.HTTPError as exc:
            self.result.errors.append(f"POST {plan.actions_path}: {type(exc).__name__}: {exc}")
            return
        if response.status_code == 201:
            self.result.acknowledged.append((plan.run_id, response.json()["seq"]))
        elif 400 <= response.status_code < 500:
            self.result.refused += 1  # e.g. the item is not delivered yet: the run said no
        else:
            self.result.errors.append(f"POST {plan.actions_path}: HTTP {response.status_code}")
