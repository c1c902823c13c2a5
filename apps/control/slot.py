"""The single default slot the SentinelBench-compatible flat endpoints operate on.

The flat endpoints name no run: whoever can reach them drives the slot's run, an agent of
another run included (it needs no token for /redirect and /contact). `SENTINEL_FLAT_ENDPOINTS=off`
switches them all off (`flat_endpoint`), so that no URL outside a run's own touches that run;
the multi-run API and the harness never need them.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import wraps

from django.conf import settings
from django.db import IntegrityError, transaction
from django.http import HttpResponse, JsonResponse

from apps.control.auth import cross_site, cross_site_refusal
from events.lifecycle import LifecycleError, close, create_run
from events.models import ClockMode, Run

NO_SESSION = "No active simulation. Call /init first."
SWITCHED_OFF = (
    "the flat SentinelBench endpoints are switched off (SENTINEL_FLAT_ENDPOINTS=off): "
    "use the multi-run API under /api/runs/"
)


def flat_endpoint(
    view: Callable[..., HttpResponse], *, changes_state: bool = False
) -> Callable[..., HttpResponse]:
    """`view`, answering 404 while SENTINEL_FLAT_ENDPOINTS is off (read per request).

    An endpoint that `changes_state` refuses another site's page (403), GETs included: the
    original protocol advances, starts and closes the slot's run with GETs and takes no token
    by default, so an `<img src="http://127.0.0.1:8000/close">` on any page its operator
    visited closed the run. Its scripts (plain HTTP clients) send no browser headers and are not
    affected."""

    @wraps(view)
    def gated(request, *args, **kwargs) -> HttpResponse:
        if not settings.SENTINEL_FLAT_ENDPOINTS:
            return JsonResponse({"detail": SWITCHED_OFF}, status=404)
        if changes_state and (found := cross_site(request, reads_too=True)):
            return JsonResponse({"detail": cross_site_refusal(found)}, status=403)
        return view(request, *args, **kwargs)

    return gated


def default_run() -> Run | None:
    return Run.objects.open_default()


def require_default_run() -> Run:
    run = default_run()
    if run is None:
        raise LifecycleError(NO_SESSION)
    return run


def create_default_run(spec: dict, *, speed_factor: float, clock_mode: str = ClockMode.LIVE) -> Run:
    """Create the slot's run; the partial unique index settles a race between two /init."""
    try:
        with transaction.atomic():
            return create_run(
                spec, speed_factor=speed_factor, clock_mode=clock_mode, default_slot=True
            )
    except IntegrityError:
        current = default_run()
        raise LifecycleError(
            f"Wrong state: /init must be called in state 'preinit'. Current: '{current.status if current else 'preinit'}'."
        ) from None


def close_default_run() -> None:
    run = default_run()
    if run is not None:
        close(run)
