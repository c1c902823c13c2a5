"""The run's clock on every page response: `X-Sentinel-Sim-Time` and `X-Sentinel-Sim-Rate`.

A page of a run (anything @run_page serves under /r/<token>/, full pages and HTMX fragments
alike) answers with the simulated second it was rendered at and how many simulated seconds the
run's clock moves per wall second from then on (0 while it does not move: not started, virtual,
over). An agent that records, with each of its steps, the last reading carried forward by its
rate has its steps on the run's own clock — the clock of the run's log and of the scenario's
events — also on a fast-forward run, whose skips every later page reports. The reference agents
do (apps.browser_agent.sim_clock); a custom agent's transcript can do the same (README,
"The task timeline").

Both values are what the page itself shows (its clock, "5 min ago"), to the millisecond; they
say nothing about the scenario. A time-travel render (read-only) gets neither: it is not the
run's present.
"""

from __future__ import annotations

from asgiref.sync import iscoroutinefunction, markcoroutinefunction
from django.http import HttpRequest, HttpResponse

from apps.kit import request_attrs

SIM_TIME_HEADER = "X-Sentinel-Sim-Time"
SIM_RATE_HEADER = "X-Sentinel-Sim-Rate"


def with_sim_clock(request: HttpRequest, response: HttpResponse) -> HttpResponse:
    reading = request_attrs.sim_clock(request)
    if reading is not None:
        now, rate = reading
        response[SIM_TIME_HEADER] = f"{now:.3f}"
        response[SIM_RATE_HEADER] = f"{rate:g}"
    return response


class SimClockHeaderMiddleware:
    """Sync and async alike (as the rest of the stack), so an ASGI request takes no thread hop."""

    sync_capable = True
    async_capable = True

    def __init__(self, get_response) -> None:
        self.get_response = get_response
        self.is_async = iscoroutinefunction(get_response)
        if self.is_async:
            markcoroutinefunction(self)

    def __call__(self, request: HttpRequest):
        if self.is_async:
            return self._acall(request)
        return with_sim_clock(request, self.get_response(request))

    async def _acall(self, request: HttpRequest) -> HttpResponse:
        return with_sim_clock(request, await self.get_response(request))
