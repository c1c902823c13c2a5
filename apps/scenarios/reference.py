"""What a scenario author needs without reading code: an environment's event types with their
payload fields, its evaluation tables with their columns, and a check of `eval_sql` against
those tables.

The tables are the ones grading builds (`events.evaluation.GradingSnapshot`) from the
environment's initial state: empty of scenario data, but with every table and column, so a
syntax error or an unknown column shows when the scenario is saved, not when a run is graded.
"""

from __future__ import annotations

import sqlite3
from dataclasses import dataclass
from functools import lru_cache

from events.catalog import load_catalog
from events.evaluation import GradingSnapshot
from events.registry import UnknownEnvironment, get_environment
from events.sandbox import run_eval_sql
from events.schemas import SchemaField, schema_fields


@dataclass(frozen=True)
class EventTypeReference:
    name: str
    help: str
    fields: tuple[SchemaField, ...]


@dataclass(frozen=True)
class TableReference:
    name: str
    columns: tuple[str, ...]


def _snapshot(environment_name: str) -> GradingSnapshot:
    environment = get_environment(environment_name)
    return GradingSnapshot(
        environment=environment,
        state=environment.initial_state(load_catalog()),
        # Every baseline an eval_sql may read from session_meta, with a placeholder value.
        baselines={name: 0 for name in environment.baselines},
        now=0.0,
        speed_factor=1.0,
        event_timeline_end=1.0,
    )


def event_types(environment_name: str) -> list[EventTypeReference]:
    """The environment's scenario event types, by name (empty for an unknown environment)."""
    try:
        environment = get_environment(environment_name)
    except UnknownEnvironment:
        return []
    return [
        EventTypeReference(name, event_type.help, tuple(schema_fields(event_type.schema)))
        for name, event_type in sorted(environment.event_types.items())
    ]


@lru_cache(maxsize=64)
def evaluation_tables(environment_name: str) -> tuple[TableReference, ...]:
    """The tables and columns eval_sql can read (session_meta included)."""
    try:
        snapshot = _snapshot(environment_name)
    except UnknownEnvironment:
        return ()
    conn = sqlite3.connect(":memory:")
    try:
        snapshot.write(conn)
        names = [
            row[0]
            for row in conn.execute(
                "SELECT name FROM sqlite_master WHERE type IN ('table', 'view') ORDER BY name"
            )
        ]
        return tuple(
            TableReference(
                name, tuple(row[1] for row in conn.execute(f'PRAGMA table_info("{name}")'))
            )
            for name in names
        )
    finally:
        conn.close()


def eval_sql_problem(environment_name: str, sql: str) -> str | None:
    """Why `sql` cannot run against the environment's evaluation tables, or None if it runs."""
    if not sql.strip():
        return None
    try:
        snapshot = _snapshot(environment_name)
    except UnknownEnvironment as error:
        return str(error)
    outcome = run_eval_sql(sql, snapshot.write)
    return None if outcome.ok else outcome.error
