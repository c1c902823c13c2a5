"""Turning authored timeline entries into logged events, exactly once, on time.

`fire_due(run)` is the one function that fires entries. It is called lazily before every read
or write of a run's state (zero staleness) and by the ticker (so open pages get pushes). Both
may run at once in many processes: `(run, timeline_index)` is unique, so each entry is logged
exactly once whoever gets there first.

Each process remembers, per run, the first entry it knows is not fired yet, so the usual call on
a page view — nothing due — costs no query. Entries are never unfired, so that hint can only lag
(another process fired more), and a lagging hint is harmless: the entry is found already fired.
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass, field

from django.db.models import Max

from events.clock import CLOCK_FIELDS, sim_now, wall_due, wall_now
from events.models import Event, EventKind, Run, RunStatus
from events.notifications import log_grew
from events.store import TimelineEntryAlreadyFired, append_entries, append_event

# Entries the tickers fire for one run per turn: a run with 15,000 entries due at once used to
# fire them in one loop, holding every other run's events back by seconds. Between its batches
# every other due run has its turn, and a run closed meanwhile is read as closed and stops.
TICK_BATCH = 25
# Entries due together are logged in one transaction of up to this many (store.append_entries).
FIRE_CHUNK = 500


@dataclass
class FireResult:
    fired: list[Event] = field(default_factory=list)
    next_index: int = 0  # the first timeline entry not fired yet
    more: bool = False  # stopped at its batch limit with entries still due


# (run pk, run token) → first timeline entry not known to be fired. The token makes the key
# unique across databases and rolled-back test runs that reuse a pk.
_next_unfired: dict[tuple[int, str], int] = {}
HINTS_KEPT = 4096


def _remember_next_unfired(run: Run, index: int) -> None:
    if len(_next_unfired) >= HINTS_KEPT:  # forget the oldest run: a lost hint costs one query
        _next_unfired.pop(next(iter(_next_unfired)), None)
    key = (run.pk, run.token)
    _next_unfired[key] = max(index, _next_unfired.get(key, 0))


def forget(run: Run) -> None:
    """Drop the hint of a closed run (nothing fires for it again)."""
    _next_unfired.pop((run.pk, run.token), None)


def _first_unfired(run: Run) -> int:
    known = _next_unfired.get((run.pk, run.token))
    return fired_through(run) + 1 if known is None else known


def _lateness_ms(run: Run, entry: dict, on_time: bool, recorded: float) -> float | None:
    # Preloads fire at init, before a live clock starts: no lateness to speak of.
    due = wall_due(run, entry["time"]) if on_time else None
    return None if due is None else max(0.0, (recorded - due) * 1000.0)


def _fire_together(run: Run, timeline: list, chunk: range, on_time: bool) -> list[Event] | None:
    """The entries of `chunk`, all due, logged in one transaction; None if another firer got
    to any of them first (then each is fired on its own, exactly once)."""
    recorded = wall_now()
    return append_entries(
        run.pk,
        [
            {
                "run_id": run.pk,
                "at": timeline[index]["time"],
                "kind": EventKind.SCENARIO,
                "type": timeline[index]["type"],
                "payload": timeline[index].get("payload") or {},
                "recorded_at": recorded,
                "timeline_index": index,
                "lateness_ms": _lateness_ms(run, timeline[index], on_time, recorded),
            }
            for index in chunk
        ],
    )


def _fire_one_by_one(run: Run, timeline: list, chunk: range, on_time: bool) -> list[Event]:
    fired = []
    for index in chunk:
        entry, recorded = timeline[index], wall_now()
        with contextlib.suppress(TimelineEntryAlreadyFired):  # another firer logged it first
            fired.append(
                append_event(
                    run,
                    EventKind.SCENARIO,
                    entry["type"],
                    entry.get("payload") or {},
                    at=entry["time"],
                    timeline_index=index,
                    lateness_ms=_lateness_ms(run, entry, on_time, recorded),
                    recorded_at=recorded,
                )
            )
    return fired


def live_runs():
    """Runs whose live clock is running: what every ticker backend watches.

    The scenario column is deferred: Run.spec serves it from a per-process cache."""
    return Run.objects.filter(status=RunStatus.RUNNING_AUTO, closed_at__isnull=True).defer(
        "scenario"
    )


def fired_through(run: Run) -> int:
    """Index of the last fired timeline entry, −1 when none."""
    last = Event.objects.filter(run_id=run.pk, timeline_index__isnull=False).aggregate(
        m=Max("timeline_index")
    )["m"]
    return -1 if last is None else last


def next_wake(run: Run, next_index: int) -> float | None:
    """Wall time at which a running run next needs firing: its next entry or its timeline end
    (None: not started). A skip makes it sooner, so a skip wakes the ticker to read it again."""
    timeline = run.timeline
    due_sim = run.event_timeline_end
    if next_index < len(timeline):
        due_sim = min(due_sim, timeline[next_index]["time"])
    return wall_due(run, due_sim)


def fire_due(
    run: Run,
    *,
    wall: float | None = None,
    next_index: int | None = None,
    reload: bool = True,
    limit: int | None = None,
) -> FireResult:
    """Fire every timeline entry due at the run's current simulated time, in order — or, with
    `limit`, at most that many (the tickers' batches: `FireResult.more` says some are left).

    Reloads the run first: the caller's copy may be stale (another process may have started,
    advanced, completed or closed it); `reload=False` is for a caller that has just read it.
    `next_index` is a hint from a caller that tracks the run (the ticker). A hint that lags is
    harmless (the unique index still fires each entry once); one ahead of the log would skip
    entries, which is why callers only ever take it from `fired_through() + 1` or a previous
    `FireResult.next_index`.
    """
    if reload:
        run.reread(*CLOCK_FIELDS, "closed_at")
    if run.closed_at is not None:
        return FireResult()
    wall = wall_now() if wall is None else wall
    now = sim_now(run, wall)
    result = fire_through(run, now, next_index=next_index, limit=limit)
    if not result.more and run.status == RunStatus.RUNNING_AUTO and now >= run.event_timeline_end:
        # The live clock ran out: the run completes at the end of its timeline. Conditional
        # write so only one caller performs the transition.
        Run.objects.filter(pk=run.pk, status=RunStatus.RUNNING_AUTO).update(
            status=RunStatus.COMPLETED, sim_time=run.event_timeline_end
        )
        run.reread("status", "sim_time")
    return result


def fire_through(
    run: Run,
    upto: float,
    *,
    next_index: int | None = None,
    on_time: bool = True,
    limit: int | None = None,
) -> FireResult:
    """Fire every unfired timeline entry scheduled at or before simulated second `upto`, in
    order, each at its own time (at most `limit` of them, when given). `on_time=False` for
    entries a skip brought (events.fastforward): they were never due on a wall clock, so they
    carry no lateness."""
    result = FireResult()
    timeline = run.timeline
    index = _first_unfired(run) if next_index is None else next_index
    end = index
    while end < len(timeline) and timeline[end]["time"] <= upto:
        if limit is not None and end - index >= limit:
            result.more = True
            break
        end += 1
    while index < end:
        chunk = range(index, min(end, index + FIRE_CHUNK))
        fired = _fire_together(run, timeline, chunk, on_time) if len(chunk) > 1 else None
        result.fired.extend(
            fired if fired is not None else _fire_one_by_one(run, timeline, chunk, on_time)
        )
        index = chunk.stop
    result.next_index = index
    _remember_next_unfired(run, index)
    if result.fired:
        log_grew(run.pk, result.fired[-1].seq)  # open pages of this run get pushed
    return result
