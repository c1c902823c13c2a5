"""Celery backend of the ticker: the same `fire_due`, scheduled at each run's due time."""

from __future__ import annotations

from datetime import UTC, datetime

from celery import shared_task

from events.clock import wall_now
from events.models import Run, RunStatus
from events.retention import purge_if_due
from events.scheduler import TICK_BATCH, fire_due, fired_through, live_runs, next_wake

HORIZON_S = 2.0  # schedule precise wake-ups for what falls due before the next heartbeat+


def _schedule(run: Run, next_index: int) -> None:
    if run.status != RunStatus.RUNNING_AUTO or run.started_at is None or run.closed_at is not None:
        return
    at = next_wake(run, next_index)
    if at is None:  # not started (checked above already: next_wake says so in its type)
        return
    if at - wall_now() <= HORIZON_S:
        fire_run.apply_async((run.pk,), eta=datetime.fromtimestamp(max(at, wall_now()), tz=UTC))


@shared_task(name="events.fire_run", ignore_result=True)
def fire_run(run_id: int) -> None:
    run = Run.objects.filter(pk=run_id).first()
    if run is None:
        return
    result = fire_due(run, limit=TICK_BATCH)  # more due: re-queued behind other runs' tasks
    _schedule(
        run, result.next_index
    )  # chain to the next entry: precise timing without a fast heartbeat


@shared_task(name="events.heartbeat", ignore_result=True)
def heartbeat() -> None:
    """Beat calls this every second: fire what is due, schedule what falls due soon."""
    now = wall_now()
    for run in live_runs():
        next_index = fired_through(run) + 1
        at = next_wake(run, next_index)
        if at is not None and at <= now:  # None: not started (the in-process ticker skips it too)
            next_index = fire_due(run, next_index=next_index, limit=TICK_BATCH).next_index
        _schedule(run, next_index)


@shared_task(name="events.purge_runs", ignore_result=True)
def purge_runs() -> None:
    """Beat calls this daily: old runs go (events.retention)."""
    purge_if_due()
