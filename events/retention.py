"""Old runs are deleted, so a server that runs for months does not keep every run it served.

A run older than `SENTINEL_RUN_RETENTION_DAYS` (default 30; 0 keeps every run) is deleted with
its log and its replay verdicts. Harness results keep their own copy of what they need (the
result folder's `events.jsonl`, and the task's row, which only loses its link to the run), so
a published result set never depends on the server still holding its runs.

`manage.py purge_runs` does it on demand; the ticker (either backend) does it once a day.
"""

from __future__ import annotations

import time
from datetime import timedelta

from django.conf import settings
from django.utils import timezone

from events.models import Run

DAY_S = 86_400.0
_last_purge = -DAY_S  # monotonic seconds, this process


def retention_days() -> float:
    return float(getattr(settings, "SENTINEL_RUN_RETENTION_DAYS", 30))


def purge_runs(*, older_than: timedelta) -> int:
    """Delete runs created more than `older_than` ago; how many were deleted."""
    cutoff = timezone.now() - older_than
    deleted = 0
    # In batches: one huge DELETE (with its cascade to the events) would hold the database.
    while ids := list(Run.objects.filter(created_at__lt=cutoff).values_list("pk", flat=True)[:500]):
        Run.objects.filter(pk__in=ids).delete()
        deleted += len(ids)
    return deleted


def purge_if_due() -> int | None:
    """Purge when the last purge in this process was a day ago or more (None: not due, or off)."""
    global _last_purge
    days = retention_days()
    now = time.monotonic()
    if days <= 0 or now - _last_purge < DAY_S:
        return None
    _last_purge = now
    return purge_runs(older_than=timedelta(days=days))
