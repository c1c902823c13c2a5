"""State as of any log position: `state_at(run, seq)` folds catalog + events.

The cache keeps, per run, the last state folded and its seq, and fast-forwards from there by
applying only the newer events. States are immutable, so a cached state can be handed out
without copying. The cache is an optimisation behind `state_at`, never a second source of truth:
a fold from scratch gives the same state (tested).

`folded_state(run)` also says where the state stands in the log, including its last scenario or
action event (what live pages track). The fold sees every event anyway; asking the log instead
would scan every page view the run has logged.
"""

from __future__ import annotations

import functools
import json
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from django.db import connection, connections

from events.catalog import load_catalog
from events.lru import LRU
from events.models import CONTACT_GET, CONTACT_POST, Event, EventKind, Run, column_field
from events.notifications import LIVE_KINDS
from events.registry import EMPTY, Environment, LoggedEvent, get_environment

CACHE_SIZE = 512

_FIELDS = ("seq", "at", "kind", "type", "payload")


def logged_events(run_id: int, after: int = 0, upto: int | None = None) -> list[LoggedEvent]:
    """The run's events with `after` < seq ≤ `upto`, in order.

    Every page request reads the log's tail, usually one or two events: SQL written once per
    database instead of a queryset built per call (the ORM's building was ten times the read).
    """
    params = [run_id, after] if upto is None else [run_id, after, upto]
    with connection.cursor() as cursor:
        cursor.execute(_logged_events_sql(connection.alias, bounded=upto is not None), params)
        rows = cursor.fetchall()
    payload = Event._meta.get_field("payload")
    column = payload.cached_col  # the expression Django itself passes for a column read
    return [
        LoggedEvent(seq, at, kind, type_, payload.from_db_value(raw, column, connection))
        for seq, at, kind, type_, raw in rows
    ]


@functools.cache
def _logged_events_sql(alias: str, *, bounded: bool) -> str:
    quote = connections[alias].ops.quote_name
    columns = ", ".join(quote(column_field(Event, name).column) for name in _FIELDS)
    seq = quote("seq")
    return (
        f"SELECT {columns} FROM {quote(Event._meta.db_table)} "
        f"WHERE {quote('run_id')} = %s AND {seq} > %s {f'AND {seq} <= %s ' if bounded else ''}"
        f"ORDER BY {seq}"
    )


def initial_state(run: Run) -> Any:
    environment = get_environment(run.environment)
    return environment.initial_state(load_catalog(run.catalog_dir))


@dataclass(frozen=True)
class Folded:
    """A state, the baselines the core captured on the way, and the log position folded to."""

    state: Any
    seq: int  # the last event folded (0: none)
    live_seq: int  # the last scenario or action event folded (0: none)
    baselines: Mapping[str, Any] = field(default_factory=lambda: EMPTY)  # after the last preload
    agent_bytes: int = 0  # the size of what the agent logged: its actions', views' and contacts'


AGENT_KINDS = (EventKind.ACTION, EventKind.VIEW)
AGENT_LIFECYCLE = (CONTACT_GET, CONTACT_POST)  # the agent's own lifecycle entries


def by_agent(event: LoggedEvent) -> bool:
    """Whether the agent wrote `event` (an action, a page view, a contact): what its budget
    counts (events/commands.py)."""
    return event.kind in AGENT_KINDS or (
        event.kind == EventKind.LIFECYCLE and event.type in AGENT_LIFECYCLE
    )


def payload_bytes(payload: Mapping[str, Any]) -> int:
    """A payload's size as stored (JSON; ASCII-escaped, so characters are bytes)."""
    return len(json.dumps(payload))


def _fold(environment: Environment, start: Folded, events: list[LoggedEvent]) -> Folded:
    if not events:
        return start
    live_seq = next((e.seq for e in reversed(events) if e.kind in LIVE_KINDS), start.live_seq)
    state, baselines = environment.fold(start.state, events, start.baselines)
    logged = sum(payload_bytes(e.payload) for e in events if by_agent(e))
    return Folded(state, events[-1].seq, live_seq, baselines, start.agent_bytes + logged)


def _fold_from_scratch(run: Run, seq: int | None, *, shared_opening: bool = True) -> Folded:
    environment = get_environment(run.environment)
    events = logged_events(run.pk, 0, seq)
    if not shared_opening:
        return _fold(environment, Folded(initial_state(run), 0, 0), events)
    opened, rest = _opening(run, environment, events)
    return _fold(environment, opened, rest)


# The fold of a log's opening — `init` and the t ≤ 0 preloads, the same for every run of a
# scenario on a catalog — shared by those runs: each reset of the flat slot made a new run whose
# first fold (its first page, its evaluation) redid the catalog's preload. A fold is a pure
# function of the catalog and the events' contents (no reducer reads `seq`, and lifecycle
# payloads never enter it: a contact's, which the agent's budget counts, ends the opening), and
# states are immutable, so one Folded can serve every such run.
# A full-preload state holds 10–100 KiB of its own beside the catalog it shares.
OPENINGS_KEPT = 64
_openings: LRU[tuple, Folded] = LRU(OPENINGS_KEPT)


def _opening_key(run: Run, opening: list[LoggedEvent]) -> tuple:
    return (
        run.environment,
        run.catalog_dir,
        run.catalog_hash,
        tuple(
            (e.seq, e.at, e.kind, e.type)
            + ((json.dumps(e.payload, sort_keys=True),) if e.kind != EventKind.LIFECYCLE else ())
            for e in opening
        ),
    )


def _opening(
    run: Run, environment: Environment, events: list[LoggedEvent]
) -> tuple[Folded, list[LoggedEvent]]:
    """The fold of `events`' opening (lifecycle and scenario events at t ≤ 0, shared across
    runs), and the events after it."""
    count = 0
    while (
        count < len(events)
        and events[count].at <= 0
        and events[count].kind in (EventKind.LIFECYCLE, EventKind.SCENARIO)
        and not by_agent(events[count])  # a contact at 0 s is this run's: its bytes are its own
    ):
        count += 1
    if not count:
        return Folded(initial_state(run), 0, 0), events
    key = _opening_key(run, events[:count])
    opened = _openings.get(key)
    if opened is None:
        opened = _fold(environment, Folded(initial_state(run), 0, 0), events[:count])
        _openings.put(key, opened)
    return opened, events[count:]


def fold_from_scratch(run: Run, seq: int | None = None) -> Folded:
    """The state as of `seq`, folded from the catalog without the caches, the shared opening's
    included (replay, checks)."""
    return _fold_from_scratch(run, seq, shared_opening=False)


_cache: LRU[tuple[int, str], Folded] = LRU(CACHE_SIZE)


def clear_cache() -> None:
    _cache.clear()
    _openings.clear()


def forget(run: Run) -> None:
    """Drop the run's kept fold (a closed run's state is ≈1 MiB nobody reads again here)."""
    _cache.pop((run.pk, run.catalog_hash))


def folded_state(run: Run, seq: int | None = None) -> Folded:
    """The state of `run` as of log position `seq` (default: the whole log), with its position."""
    key = (run.pk, run.catalog_hash)
    cached = _cache.get(key)
    if cached is not None and (seq is None or cached.seq <= seq):
        newer = logged_events(run.pk, cached.seq, seq)
        result = _fold(get_environment(run.environment), cached, newer)
    else:
        result = _fold_from_scratch(run, seq)
    if seq is None or cached is None or result.seq >= cached.seq:
        # Unless a concurrent caller already folded further.
        _cache.put(key, result, unless=lambda current: current.seq > result.seq)
    return result


def state_at(run: Run, seq: int | None = None) -> Any:
    """The environment state of `run` as of log position `seq` (default: the whole log)."""
    return folded_state(run, seq).state


def folded_after(run: Run, before: Folded, event: Event, state: Any) -> Folded:
    """`before` moved past `event`, which the caller logged and applied itself (`state`).

    When `event` is the very next entry of the log, that is the fold: it is kept as the run's
    cached fold and returned without reading the log. When someone else appended in between
    (a scenario event fired by the ticker, another tab's action), the log is folded instead.
    """
    if event.seq != before.seq + 1:
        return folded_state(run)
    live_seq = event.seq if event.kind in LIVE_KINDS else before.live_seq
    logged = before.agent_bytes + payload_bytes(event.payload)
    after = Folded(state, event.seq, live_seq, before.baselines, logged)
    _cache.put((run.pk, run.catalog_hash), after, unless=lambda current: current.seq >= after.seq)
    return after


def past_view(before: Folded, view: Event) -> Folded:
    """`before` moved past the view event `view`: views never change state, so the fold is the
    same state one entry further (valid only when `view` is the next entry)."""
    if view.seq != before.seq + 1:
        return before
    logged = before.agent_bytes + payload_bytes(view.payload)
    return Folded(before.state, view.seq, before.live_seq, before.baselines, logged)
