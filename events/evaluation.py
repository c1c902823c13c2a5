"""Grading a run (upstream-protocol.md §4), as of the agent's first contact.

The state is folded as of the log position just before the first contact (or the whole log
when the agent never made contact), so actions taken after the agent said it was done do not
count. Contact times are kept as floats: no truncation to whole seconds.
"""

from __future__ import annotations

import functools
import sqlite3
import weakref
from collections.abc import Mapping
from dataclasses import asdict, dataclass
from typing import Any

from django.db import connection, connections

from events.clock import TICKING
from events.lifecycle import CONTACT_GET, CONTACT_POST, complete
from events.lru import LRU
from events.models import Event, EventKind, Run, column_field
from events.projection import folded_state
from events.registry import Environment, get_environment
from events.sandbox import is_truthy, run_eval_sql_on, serialise, shown, write_session_meta
from events.timing import to_wall

NOOP_DETAIL = "no-op task: success requires no /contact visit"


@dataclass(frozen=True)
class Contacts:
    first_seq: int | None  # log position of the first contact of either kind
    first_at: float | None
    get_at: float | None
    post_at: float | None
    message: str | None


# Every /evaluate reads a run's contacts and counts its views and actions: SQL written once per
# database (the ORM built each query for longer than the database took to answer it).
@functools.cache
def _contacts_sql(alias: str) -> str:
    quote = connections[alias].ops.quote_name
    columns = ", ".join(
        quote(column_field(Event, name).column)
        for name in ("seq", "at", "type", "payload", "recorded_at")
    )
    return (
        f"SELECT {columns} FROM {quote(Event._meta.db_table)} "
        f"WHERE {quote('run_id')} = %s AND {quote('kind')} = %s AND {quote('type')} IN (%s, %s) "
        f"ORDER BY {quote('seq')}"
    )


@functools.cache
def _agent_counts_sql(alias: str) -> str:
    quote = connections[alias].ops.quote_name
    kind = quote("kind")
    return (
        f"SELECT COUNT(CASE WHEN {kind} = %s THEN 1 END), COUNT(CASE WHEN {kind} = %s THEN 1 END) "
        f"FROM {quote(Event._meta.db_table)} WHERE {quote('run_id')} = %s"
    )


def _contact_rows(run: Run) -> list[tuple]:
    with connection.cursor() as cursor:
        cursor.execute(
            _contacts_sql(connection.alias),
            [run.pk, EventKind.LIFECYCLE.value, CONTACT_GET, CONTACT_POST],
        )
        rows = cursor.fetchall()
    payload = Event._meta.get_field("payload")
    column = payload.cached_col  # the expression Django itself passes for a column read
    return [
        (seq, at, type_, payload.from_db_value(raw, column, connection), recorded_at)
        for seq, at, type_, raw, recorded_at in rows
    ]


def agent_counts(run: Run) -> tuple[int, int]:
    """How many views and actions the run's log holds (all of it, after contact too)."""
    with connection.cursor() as cursor:
        cursor.execute(
            _agent_counts_sql(connection.alias),
            [EventKind.VIEW.value, EventKind.ACTION.value, run.pk],
        )
        views, actions = cursor.fetchone()
    return views, actions


def contacts_of(run: Run) -> Contacts:
    rows = _contact_rows(run)
    first = rows[0] if rows else None
    first_get = next((r for r in rows if r[2] == CONTACT_GET), None)
    first_post = next((r for r in rows if r[2] == CONTACT_POST), None)

    ticking = run.clock_mode in TICKING and run.started_at is not None

    def moment(row) -> float | None:
        # The first contact froze the clock, so a later visit is logged at the frozen time;
        # on a live clock, its own moment is that time plus the wall time since, scaled.
        if row is None or not ticking:
            return None if row is None else row[1]
        assert first is not None  # `row` is one of `rows`, so there is a first one
        later = row[1] + max(0.0, row[4] - first[4]) * run.speed_factor
        return min(later, max(row[1], run.event_timeline_end))

    return Contacts(
        first_seq=first[0] if first else None,
        first_at=first[1] if first else None,
        get_at=moment(first_get),
        post_at=moment(first_post),
        message=first_post[3].get("message") if first_post else None,
    )


@dataclass(frozen=True)
class Verdict:
    success: bool
    detail: str
    evaluation_time: float
    condition_at: float | None
    contact_get_time: float | None
    contact_post_time: float | None
    contact_message: str | None
    run: int
    reaction_time: float | None
    views: int
    actions: int
    graded_at_seq: int | None

    def as_dict(self) -> dict[str, Any]:
        return asdict(self)


@dataclass(frozen=True)
class GradingSnapshot:
    """What eval_sql sees: an environment's state and captured baselines, as of one moment.

    `write` is the one builder of the grading database — evaluation, the admin's dry run,
    replay digests and the tests all build it here, so they can never disagree about it.
    """

    environment: Environment
    state: Any
    baselines: Mapping[str, Any]
    now: float  # simulated seconds (authored): what the tables are computed at
    speed_factor: float
    event_timeline_end: float  # authored seconds

    def session_meta(self) -> dict[str, Any]:
        meta: dict[str, Any] = {
            # Upstream reports these in wall seconds (its /init divides by speed_factor).
            "simulation_time": float(to_wall(self.now, self.speed_factor)),
            "event_timeline_end": float(to_wall(self.event_timeline_end, self.speed_factor)),
        }
        meta.update({f"baseline_{name}": value for name, value in self.baselines.items()})
        return meta

    def write(self, conn: sqlite3.Connection) -> None:
        write_session_meta(conn, self.session_meta())
        self.environment.materialize(self.state, self.now, conn)

    def serialised(self) -> bytes:
        """The grading database `write` builds, serialised for the sandbox — built once per
        state, moment and meta: runs of one scenario evaluated at the same point of their
        timeline share the state of their log's opening (events.projection), and so the
        tables. A state that cannot be held weakly is not kept."""
        meta = tuple((name, str(value)) for name, value in self.session_meta().items())
        key = (id(self.state), self.environment.name, repr(self.now), meta)
        kept = _databases.get(key)
        if kept is not None and kept[0]() is self.state:
            return kept[1]
        database = serialise(self.write)
        try:
            held = weakref.ref(self.state, lambda _: _databases.pop(key))
        except TypeError:
            return database
        _databases.put(key, (held, database))
        return database


# Serialised grading databases by the state (held weakly: a key's id is never another state's)
# and moment they were built for; bounded in bytes (a full-preload database is 36–120 KiB).
DATABASES_KEPT, DATABASE_BYTES_KEPT = 64, 8 * 1024 * 1024
_databases: LRU[tuple, tuple[weakref.ref, bytes]] = LRU(
    DATABASES_KEPT, budget=DATABASE_BYTES_KEPT, weigh=lambda kept: len(kept[1])
)


def grading_snapshot(
    run: Run, seq: int | None = None, *, now: float | None = None
) -> GradingSnapshot:
    """The run as of log position `seq` (default: all of it), at simulated time `now` (default:
    the run's clock, which a contact or an evaluation has frozen)."""
    folded = folded_state(run, seq)
    return GradingSnapshot(
        environment=get_environment(run.environment),
        state=folded.state,
        baselines=folded.baselines,
        now=run.sim_time if now is None else now,
        speed_factor=run.speed_factor,
        event_timeline_end=run.event_timeline_end,
    )


def grade(run: Run) -> tuple[bool, str, Contacts, int | None]:
    contacts = contacts_of(run)
    graded_at = None if contacts.first_seq is None else contacts.first_seq - 1
    contacted = contacts.first_seq is not None
    condition_at = run.condition_at
    noop = condition_at is None
    sql = (run.spec.get("eval_sql") or "").strip()
    if not sql:
        if noop:
            return not contacted, NOOP_DETAIL, contacts, graded_at
        return False, "no eval_sql configured", contacts, graded_at

    # Graded as of the first contact, on the values of that moment (prices, counts that move).
    snapshot = grading_snapshot(run, graded_at, now=contacts.first_at)
    outcome = run_eval_sql_on(sql, snapshot.serialised)
    if not outcome.ok:
        return False, outcome.error, contacts, graded_at
    sql_pass = is_truthy(outcome.value)
    detail = f"eval_sql returned {shown(outcome.value)}"
    if noop:
        if contacted:
            detail += f"; {NOOP_DETAIL}"
        return (not contacted) and sql_pass, detail, contacts, graded_at
    if not contacted:
        return False, detail + "; the agent never visited /contact", contacts, graded_at
    assert condition_at is not None and contacts.first_at is not None  # not noop; contacted
    if contacts.first_at < condition_at:
        early = to_wall(condition_at - contacts.first_at, run.speed_factor)
        return (
            False,
            detail + f"; contacted {early:.2f} s before the condition held",
            contacts,
            graded_at,
        )
    return sql_pass, detail, contacts, graded_at


def evaluate(run: Run) -> Verdict:
    """Complete the run (freezing its clock) and grade it."""
    complete(run)
    success, detail, contacts, graded_at = grade(run)
    sf = run.speed_factor
    reaction = None
    if success and run.condition_at is not None and contacts.first_at is not None:
        reaction = to_wall(contacts.first_at - run.condition_at, sf)
    views, actions = agent_counts(run)  # one read of the log for both
    return Verdict(
        success=success,
        detail=detail,
        evaluation_time=to_wall(run.sim_time, sf),
        condition_at=to_wall(run.condition_at, sf),
        contact_get_time=to_wall(contacts.get_at, sf),
        contact_post_time=to_wall(contacts.post_at, sf),
        contact_message=contacts.message,
        run=run.pk,
        reaction_time=reaction,
        views=views,
        actions=actions,
        graded_at_seq=graded_at,
    )
