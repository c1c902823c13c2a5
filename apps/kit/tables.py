"""Evaluation tables: each column declared with the value it holds, written in one call.

An environment's `materialize(state, now, conn)` writes upstream-compatible tables so that the
original `eval_sql` runs unchanged. A table is declared as its name, where its rows come from,
and `{column definition: getter}`: the DDL, the INSERT and every row are derived from that one
mapping, so a column can never be added to the DDL and forgotten (or misplaced) in the rows.

    EMAILS = Table.items("emails", {                  # a row per item of `state.emails`
        "id TEXT PRIMARY KEY": "id",                  # an attribute of the row
        "attachment_name TEXT": "attachment_names",
        "isRead INTEGER": lambda e: e.read,           # or a function of the row
    })
    EMAIL_STATES = Table.keyed("email_states", "states", {
        "email_id TEXT PRIMARY KEY": KEY,             # the mapping's key
        "isRead INTEGER": "is_read",                  # attributes of the value (or VALUE)
    })
    SENT = Table("sent", lambda mail, now: mail.sent, named("id TEXT", "subject TEXT"))  # any rows
    materialize = tables(EMAILS, EMAIL_STATES, SENT)
"""

from __future__ import annotations

import sqlite3
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from functools import cached_property
from operator import attrgetter
from typing import Any, Generic, NamedTuple, TypeVar

S = TypeVar("S")

Getter = str | Callable[[Any], Any]  # an attribute name (dotted allowed) or a function of a row
Rows = Callable[[S, float], Iterable[Any]]  # (state, now) → the rows


class Keyed(NamedTuple):
    """A row of a `Table.keyed` table: one entry of a state mapping."""

    key: Any
    value: Any


def VALUE(row: Keyed) -> Any:  # a function named as a constant, like KEY
    """The value of a `Table.keyed` row whose mapping holds plain values (message id → read)."""
    return row.value


def named(*columns: str) -> dict[str, str]:
    """`{column definition: attribute}` for columns named after the attribute they read:
    `named("id TEXT", "number INTEGER")` → `{"id TEXT": "id", "number INTEGER": "number"}`."""
    return {column: column.split()[0] for column in columns}


def KEY(row: Keyed) -> Any:  # a function named as a constant: it reads as one in a column mapping
    """The mapping key of a `Table.keyed` row (e.g. the email id of an email's state)."""
    return row.key


@dataclass(frozen=True)
class Table(Generic[S]):
    name: str
    rows: Rows[S]
    # SQL column definition (e.g. "id TEXT PRIMARY KEY", "isRead INTEGER") → its value.
    columns: Mapping[str, Getter]

    @classmethod
    def keyed(
        cls,
        name: str,
        mapping: str | Callable[[S, float], Mapping[Any, Any]],
        columns: Mapping[str, Getter],
    ) -> Table[S]:
        """A table of one row per entry of a mapping — the state's field `mapping` (id →
        per-item state), or one computed by `mapping(state, now)`: `KEY` is the key, `VALUE`
        the value, an attribute name reads the value."""
        value_columns = {
            column: getter if callable(getter) else _of_value(getter)
            for column, getter in columns.items()
        }
        if callable(mapping):
            compute = mapping
            return cls(name, lambda state, now: _entries(compute(state, now)), value_columns)
        return cls(name, lambda state, now: _entries(getattr(state, mapping)), value_columns)

    @classmethod
    def items(cls, name: str, columns: Mapping[str, Getter], mapping: str = "") -> Table[S]:
        """A table of one row per item of the state's mapping `mapping` (id → item; by
        default the table's own name): `Table.items("issues", named("id TEXT", "title TEXT"))`."""
        read = attrgetter(mapping or name)
        return cls(name, lambda state, now: read(state).values(), columns)

    @cached_property
    def _getters(self) -> tuple[Callable[[Any], Any], ...]:
        return tuple(
            getter if callable(getter) else attrgetter(getter) for getter in self.columns.values()
        )

    @cached_property
    def _create(self) -> str:
        return f"CREATE TABLE {self.name} ({', '.join(self.columns)})"

    @cached_property
    def _insert(self) -> str:
        return f"INSERT INTO {self.name} VALUES ({', '.join('?' * len(self.columns))})"

    def write(self, conn: sqlite3.Connection, state: S, now: float) -> None:
        """Create the table and insert one row per item of `rows(state, now)`."""
        getters = self._getters
        conn.execute(self._create)
        conn.executemany(
            self._insert, ([_sql(get(row)) for get in getters] for row in self.rows(state, now))
        )


def tables(*declared: Table[S]) -> Callable[[S, float, sqlite3.Connection], None]:
    """An environment's `materialize`: every declared table, written in order."""

    def materialize(state: S, now: float, conn: sqlite3.Connection) -> None:
        for table in declared:
            table.write(conn, state, now)

    materialize.__doc__ = "Write " + ", ".join(f"`{t.name}`" for t in declared) + "."
    return materialize


def _entries(mapping: Mapping[Any, Any]) -> Iterable[Keyed]:
    return (Keyed(key, value) for key, value in mapping.items())


def _of_value(name: str) -> Callable[[Keyed], Any]:
    get = attrgetter(name)
    return lambda row: get(row.value)


def _sql(value: Any) -> Any:
    # SQLite has no booleans: upstream stored them as 0/1 and eval_sql compares with integers.
    return int(value) if isinstance(value, bool) else value


def item_states(item: str, columns: Mapping[str, Getter], mapping: str = "") -> Table[Any]:
    """The original's `<item>_states` table: one row per entry of the state's mapping `mapping`
    (by default the table's own name), keyed `<item>_id`, then `columns` read from the value:
    `item_states("post", {"isLiked INTEGER": "is_liked"})`."""
    name = f"{item}_states"
    return Table.keyed(name, mapping or name, {f"{item}_id TEXT PRIMARY KEY": KEY, **columns})
