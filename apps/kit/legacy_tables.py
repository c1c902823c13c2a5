"""TRANSITIONAL (kit 2): the old column-list Table, until every environment declares its tables in apps.kit.tables. Delete when nothing imports it.

An environment's `materialize(state, now, conn)` writes upstream-compatible tables so that the
original `eval_sql` runs unchanged. Each is declared as its name and column definitions; the
INSERT (and its placeholders) is derived from them, so a column can never be added to the DDL
and forgotten in the rows.
"""

from __future__ import annotations

import sqlite3
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any


@dataclass(frozen=True)
class Table:
    name: str
    columns: Sequence[str]  # SQL column definitions, e.g. "id TEXT PRIMARY KEY", "isRead INTEGER"

    @cached_property
    def _insert(self) -> str:
        return f"INSERT INTO {self.name} VALUES ({', '.join('?' * len(self.columns))})"

    def write(self, conn: sqlite3.Connection, rows: Iterable[Sequence[Any]]) -> None:
        """Create the table and insert `rows` (each a sequence in column order; bools as 0/1)."""
        conn.execute(f"CREATE TABLE {self.name} ({', '.join(self.columns)})")
        conn.executemany(self._insert, ([_sql(v) for v in row] for row in rows))


def _sql(value: Any) -> Any:
    # SQLite has no booleans: upstream stored them as 0/1 and eval_sql compares with integers.
    return int(value) if isinstance(value, bool) else value
