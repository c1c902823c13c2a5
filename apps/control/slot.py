"""The single default slot the SentinelBench-compatible flat endpoints operate on."""

from __future__ import annotations

from django.db import IntegrityError, transaction

from events.lifecycle import LifecycleError, close, create_run
from events.models import Run

NO_SESSION = "No active simulation. Call /init first."


def default_run() -> Run | None:
    return Run.objects.filter(is_default_slot=True, closed_at__isnull=True).first()


def require_default_run() -> Run:
    run = default_run()
    if run is None:
        raise LifecycleError(NO_SESSION)
    return run


def create_default_run(spec: dict, *, speed_factor: float) -> Run:
    """Create the slot's run; the partial unique index settles a race between two /init."""
    try:
        with transaction.atomic():
            return create_run(spec, speed_factor=speed_factor, default_slot=True)
    except IntegrityError:
        current = default_run()
        raise LifecycleError(
            f"Wrong state: /init must be called in state 'preinit'. Current: '{current.status if current else 'preinit'}'."
        ) from None


def close_default_run() -> None:
    run = default_run()
    if run is not None:
        close(run)
