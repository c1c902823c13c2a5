"""Every item there is: what the act-on-everything control agent (`bench validate`) acts on.

An agent that never monitors performs the task's action on every item it can see, then reports
at the deadline. "The task's action" is each step of the scenario's `solution`; "every item" is
every id of the same kind in the grading database (every track for `like_track`, every message
for a reply, every stock for an order, …) as the scenario's timeline leaves it at that moment,
folded here in memory from the catalog, as the admin's dry run does. One declarative rule for
all ten environments, instead of ten scrapers of their pages.
"""

from __future__ import annotations

import contextlib
import re
import sqlite3
from collections.abc import Iterator
from typing import Any

from events.catalog import load_catalog
from events.evaluation import GradingSnapshot
from events.registry import EMPTY, LoggedEvent, get_environment

# Kinds of id whose items are listed under another name in the grading database.
ALSO = {
    "user_id": ("SELECT authorId FROM posts", "SELECT authorId FROM stories"),
    "conversation_id": ("SELECT id FROM conversations", "SELECT id FROM messages"),
}


def ids_of_kind(conn: sqlite3.Connection, key: str) -> set:
    """Every value a payload field `key` (`track_id`, `symbol`, …) can take: the columns of
    that name (or its camelCase), the `id` of the tables named after it, and ALSO."""
    camel = re.sub(r"_(\w)", lambda m: m.group(1).upper(), key)
    prefix = key.removesuffix("_id")
    values: set = set()
    tables = [name for (name,) in conn.execute("SELECT name FROM sqlite_master WHERE type='table'")]
    for table in tables:
        for column in (row[1] for row in conn.execute(f'PRAGMA table_info("{table}")')):
            named = column in (key, camel)
            own_id = column == "id" and table.startswith(prefix) and "_" not in table
            if named or own_id:
                values |= {v for (v,) in conn.execute(f'SELECT "{column}" FROM "{table}"')}
    for sql in ALSO.get(key, ()):
        with contextlib.suppress(sqlite3.OperationalError):  # not this environment's table
            values |= {v for (v,) in conn.execute(sql)}
    values.discard(None)
    return values


def on_every_item(conn: sqlite3.Connection, step: dict) -> Iterator[dict]:
    """The step's payload once per item: a reply to every message, else every id of the kind
    of its first id field (a step without one, as it is)."""
    payload = step.get("payload") or {}
    if "reply_to" in payload:
        for message, conversation in conn.execute("SELECT id, conversationId FROM messages"):
            yield {**payload, "conversation_id": conversation, "reply_to": message}
        return
    keys = [key for key in payload if key.endswith("_id") or key == "symbol"]
    if not keys:
        yield payload
        return
    for value in sorted(ids_of_kind(conn, keys[0]), key=str):
        yield {**payload, keys[0]: value}


def grading_tables(spec: dict[str, Any], at: float) -> sqlite3.Connection:
    """The grading database of a scenario played with no agent until simulated time `at`."""
    environment = get_environment(spec["environment"])
    state, baselines = environment.initial_state(load_catalog()), EMPTY
    timeline = sorted(spec.get("events") or [], key=lambda e: float(e["time"]))
    events = [
        LoggedEvent(seq, float(e["time"]), "scenario", e["type"], e.get("payload") or {})
        for seq, e in enumerate(timeline, 1)
        if float(e["time"]) <= at
    ]
    state, baselines = environment.fold(state, events, baselines)
    conn = sqlite3.connect(":memory:")
    end = float(spec["event_timeline_end"])
    GradingSnapshot(environment, state, baselines, at, 1.0, end).write(conn)
    return conn


def every_item_steps(spec: dict[str, Any], at: float) -> list[dict]:
    """The scenario's solution steps on every item there is at simulated time `at`."""
    conn = grading_tables(spec, at)
    try:
        return [
            {"action": step["action"], "payload": payload}
            for step in spec.get("solution") or []
            for payload in on_every_item(conn, step)
        ]
    finally:
        conn.close()
