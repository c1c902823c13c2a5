"""Appending to a run's log with optimistic concurrency.

`(run, seq)` is unique: a writer reads the last seq, inserts seq+1 and retries when another
writer took that number first. No table lock is held, so appends to different runs never wait
for each other (on PostgreSQL; SQLite serialises writers anyway). On PostgreSQL every append
takes its run's row first, and a writer that has lost a race (it waited on that row, and its
statement's snapshot is older than the seq the holder wrote) queues on the row before reading
the last seq again: it then cannot lose twice. Without the row, a fast writer could win every
round and starve a slower one out of its attempts.
"""

from __future__ import annotations

from typing import Any

from asgiref.sync import sync_to_async
from django.db import IntegrityError, connection, transaction

from events.clock import wall_now
from events.models import Event, Run, column_field

MAX_ATTEMPTS = 50


class AppendConflict(RuntimeError):
    pass


class TimelineEntryAlreadyFired(IntegrityError):
    """The entry was fired by another worker first: exactly-once held, nothing to do."""


def _insert_at_next_seq(run_id: int, values: dict[str, Any]) -> Event:
    """INSERT the event at MAX(seq)+1 of its run in one statement, and return it.

    One statement instead of read-then-insert: SQLite runs it as one write transaction (no
    window for another writer, no separate BEGIN/COMMIT round trips, which on a page view cost
    as much as the rest of the logging); on PostgreSQL two concurrent statements can still pick
    the same seq, and the loser's unique-constraint error sends it round `append_event`'s retry.
    """
    fields = [column_field(Event, name) for name in values]
    quote = connection.ops.quote_name
    columns = ", ".join(quote(field.column) for field in fields)
    params = [
        field.get_db_prep_save(value, connection)
        for field, value in zip(fields, values.values(), strict=True)
    ]
    table = quote(Event._meta.db_table)
    run_of = "%s"
    if connection.features.has_select_for_update:
        # Take the run's row before reading MAX(seq): a writer queued on it (see
        # `_attempt_append`) then never meets an insert in flight, so the queue is fair. The
        # lock is taken before any row is inserted, so it cannot deadlock with a queued writer.
        run_of = (
            f"(SELECT {quote('id')} FROM {quote(Run._meta.db_table)} "
            f"WHERE {quote('id')} = %s FOR NO KEY UPDATE)"
        )
    sql = (
        f"INSERT INTO {table} ({columns}, {quote('seq')}) "
        f"SELECT {', '.join(['%s'] * len(fields))}, COALESCE(MAX({quote('seq')}), 0) + 1 "
        f"FROM {table} WHERE {quote('run_id')} = {run_of} "
        f"RETURNING {quote('id')}, {quote('seq')}"
    )
    with connection.cursor() as cursor:
        cursor.execute(sql, [*params, run_id])
        pk, seq = cursor.fetchone()
    event = Event(pk=pk, seq=seq, **values)
    event._state.adding = False
    event._state.db = connection.alias
    return event


def _attempt_append(run_id: int, values: dict[str, Any], *, queue: bool) -> Event:
    if not queue and not connection.in_atomic_block:
        return _insert_at_next_seq(run_id, values)  # one statement: atomic on its own
    # Inside the caller's transaction, a savepoint: a lost race must leave that transaction usable.
    with transaction.atomic():
        if queue:  # held until commit: the writers of this run take turns (no_key: the FK
            # check of a racing insert takes KEY SHARE, which FOR UPDATE would deadlock)
            list(Run.objects.select_for_update(no_key=True).filter(pk=run_id).values_list("pk"))
        return _insert_at_next_seq(run_id, values)


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
    values = {
        "run_id": run_id,
        "at": at,
        "kind": kind,
        "type": type,
        "payload": payload or {},
        "recorded_at": recorded_at if recorded_at is not None else wall_now(),
        "timeline_index": timeline_index,
        "lateness_ms": lateness_ms,
    }
    queue = False
    for _ in range(MAX_ATTEMPTS):
        try:
            return _attempt_append(run_id, values, queue=queue)
        except IntegrityError:
            if (
                timeline_index is not None
                and Event.objects.filter(run_id=run_id, timeline_index=timeline_index).exists()
            ):
                raise TimelineEntryAlreadyFired(
                    f"timeline entry {timeline_index} already fired"
                ) from None
            queue = connection.features.has_select_for_update
            continue  # someone else took this seq: read again and retry
    raise AppendConflict(f"could not append to run {run_id} after {MAX_ATTEMPTS} attempts")


def append_entries(run_id: int, entries: list[dict[str, Any]]) -> list[Event] | None:
    """Append timeline entries (each a dict of Event fields) at the run's next consecutive
    seqs in one transaction and return them — or None, writing nothing, when another writer got
    there first (an entry already fired, a seq taken): the caller then appends them one by one.

    One `append_event` per entry is a round of the database each: a moment at which thousands of
    entries fall due (an authored burst, a skip or an advance over a long stretch) held the
    thread that fired them — a page's, a ticker's — for seconds. Here the run's writers are
    queued behind its row (as a writer that lost a race is), the last seq read once, and the
    rows written in one `executemany`."""
    names = list(entries[0])
    fields = [column_field(Event, name) for name in names]
    quote = connection.ops.quote_name
    table = quote(Event._meta.db_table)
    columns = ", ".join(quote(field.column) for field in [*fields, column_field(Event, "seq")])
    insert = f"INSERT INTO {table} ({columns}) VALUES ({', '.join(['%s'] * (len(fields) + 1))})"
    try:
        with transaction.atomic():
            if connection.features.has_select_for_update:
                list(Run.objects.select_for_update(no_key=True).filter(pk=run_id).values_list("pk"))
            with connection.cursor() as cursor:
                cursor.execute(
                    f"SELECT COALESCE(MAX({quote('seq')}), 0) FROM {table} "
                    f"WHERE {quote('run_id')} = %s",
                    [run_id],
                )
                (last,) = cursor.fetchone()
                cursor.executemany(
                    insert,
                    [
                        [
                            *(
                                field.get_db_prep_save(entry[name], connection)
                                for field, name in zip(fields, names, strict=True)
                            ),
                            last + offset,
                        ]
                        for offset, entry in enumerate(entries, 1)
                    ],
                )
    except IntegrityError:
        return None
    appended = []
    for offset, entry in enumerate(entries, 1):
        event = Event(seq=last + offset, **entry)
        event._state.adding = False
        event._state.db = connection.alias
        appended.append(event)
    return appended


aappend_event = sync_to_async(append_event, thread_sensitive=False)
