"""Run a scenario's `eval_sql` safely against a materialised snapshot.

Each evaluation gets a fresh in-memory SQLite database. The query runs as exactly one
statement, under an authorizer that allows reads only (no writes, no ATTACH, no PRAGMA) and a
progress handler that aborts it after a time limit, so a hostile or runaway query can neither
touch anything nor stall the server.
"""

from __future__ import annotations

import sqlite3
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

TIME_LIMIT_S = 2.0

# Everything a SELECT needs; every other action code (INSERT, UPDATE, DELETE, CREATE, DROP,
# ALTER, ATTACH, DETACH, PRAGMA, TRANSACTION, SAVEPOINT …) is denied.
_ALLOWED_ACTIONS = {sqlite3.SQLITE_SELECT, sqlite3.SQLITE_READ, sqlite3.SQLITE_FUNCTION}
if hasattr(sqlite3, "SQLITE_RECURSIVE"):
    _ALLOWED_ACTIONS.add(sqlite3.SQLITE_RECURSIVE)
else:  # pragma: no cover - older Python builds without the constant
    _ALLOWED_ACTIONS.add(33)


@dataclass(frozen=True)
class SqlOutcome:
    ok: bool
    value: Any = None
    error: str = ""


def _read_only(action: int, *_args) -> int:
    return sqlite3.SQLITE_OK if action in _ALLOWED_ACTIONS else sqlite3.SQLITE_DENY


def is_truthy(value: Any) -> bool:
    """SQL truth of the first column: NULL, 0, '' and numeric text equal to 0 are false.

    Upstream used Python truthiness, which made the text '0' true.
    """
    if value is None:
        return False
    if isinstance(value, str):
        text = value.strip()
        try:
            return float(text) != 0
        except ValueError:
            return text != ""
    if isinstance(value, bytes):
        return len(value) > 0
    return bool(value)


def write_session_meta(conn: sqlite3.Connection, meta: Mapping[str, Any]) -> None:
    conn.execute("CREATE TABLE session_meta (key TEXT PRIMARY KEY, value TEXT)")
    conn.executemany(
        "INSERT OR REPLACE INTO session_meta (key, value) VALUES (?, ?)",
        [(key, str(value)) for key, value in meta.items()],
    )


def run_eval_sql(
    sql: str,
    build: Callable[[sqlite3.Connection], None],
    *,
    time_limit_s: float = TIME_LIMIT_S,
) -> SqlOutcome:
    """Build the snapshot with `build(conn)`, then run `sql` read-only; never raises."""
    conn = sqlite3.connect(":memory:", check_same_thread=False)
    try:
        try:
            build(conn)
            conn.commit()
        except Exception as exc:  # a materialisation bug is a graded failure, not a 500
            return SqlOutcome(False, error=f"could not build the evaluation tables: {exc}")
        conn.set_authorizer(_read_only)
        deadline = time.monotonic() + time_limit_s
        conn.set_progress_handler(lambda: 1 if time.monotonic() > deadline else 0, 10_000)
        try:
            row = conn.execute(sql).fetchone()
        except sqlite3.ProgrammingError as exc:
            return SqlOutcome(False, error=f"eval_sql rejected: {exc}")
        except sqlite3.DatabaseError as exc:
            message = str(exc)
            if message == "interrupted":
                message = f"time limit of {time_limit_s:g} s exceeded"
            elif "not authorized" in message:
                message = "not authorized: eval_sql may only read (no writes, ATTACH or PRAGMA)"
            return SqlOutcome(False, error=f"eval_sql error: {message}")
        except Exception as exc:  # never let a query take the server down
            return SqlOutcome(False, error=f"eval_sql error: {exc}")
        return SqlOutcome(True, value=None if row is None else row[0])
    finally:
        conn.close()
