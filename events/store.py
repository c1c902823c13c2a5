"""Appending to a run's log with optimistic concurrency.

`(run, seq)` is unique: a writer reads the last seq, inserts seq+1 and retries when another
writer took that number first. No table lock is held, so appends to different runs never wait
for each other (on PostgreSQL; SQLite serialises writers anyway). A writer that has lost a race
queues on its run's row instead of racing again: otherwise a fast writer can win every round
and starve a slower one.
"""

from __future__ import annotations

from typing import Any

from asgiref.sync import sync_to_async
from django.db import IntegrityError, connection, transaction
from django.db.models import Max

from events.clock import wall_now
from events.models import Event, Run

MAX_ATTEMPTS = 50


class AppendConflict(RuntimeError):
    pass


class TimelineEntryAlreadyFired(IntegrityError):
    """The entry was fired by another worker first: exactly-once held, nothing to do."""


def _last_seq(run_id: int) -> int:
    return Event.objects.filter(run_id=run_id).aggregate(m=Max("seq"))["m"] or 0


def append_event(
    run: Run | int,
    kind: str,
    type: str,
    payload: dict[str, Any] | None = None,
    at: float = 0.0,
    *,
    timeline_index: int | None = None,
    lateness_ms: float | None = None,
    recorded_at: float | None = None,
) -> Event:
    """Append one event to the run's log and return it (with its seq)."""
    run_id = run if isinstance(run, int) else run.pk
    payload = payload or {}
    queue = False
    for _ in range(MAX_ATTEMPTS):
        try:
            with transaction.atomic():
                if queue:  # held until commit: the writers of this run take turns (no_key: the
                    # FK check of a racing insert takes KEY SHARE, which FOR UPDATE would deadlock)
                    list(Run.objects.select_for_update(no_key=True).filter(pk=run_id).values_list("pk"))
                seq = _last_seq(run_id) + 1
                return Event.objects.create(
                    run_id=run_id,
                    seq=seq,
                    at=at,
                    kind=kind,
                    type=type,
                    payload=payload,
                    recorded_at=recorded_at if recorded_at is not None else wall_now(),
                    timeline_index=timeline_index,
                    lateness_ms=lateness_ms,
                )
        except IntegrityError:
            if timeline_index is not None and Event.objects.filter(
                run_id=run_id, timeline_index=timeline_index
            ).exists():
                raise TimelineEntryAlreadyFired(f"timeline entry {timeline_index} already fired") from None
            queue = connection.features.has_select_for_update
            continue  # someone else took this seq: read again and retry
    raise AppendConflict(f"could not append to run {run_id} after {MAX_ATTEMPTS} attempts")


aappend_event = sync_to_async(append_event, thread_sensitive=False)
