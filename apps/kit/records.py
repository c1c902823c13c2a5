"""Catalog records (plain JSON objects) read into frozen dataclasses from declared fields.

An environment's catalog module declares once, per record type, which attribute comes from
which catalog key and how it is converted; one generic `read` builds the value, and `reader`
makes the `make(state, id, stamp)` of an `arrivals.Delivery` from a catalog table:

    CHECK = {"name": text("name"), "status": text_or("status", "pending")}
    checks = each("checks", Check, CHECK)              # a list of objects → tuple[Check]
    commit = reader("microhub", "commits", Commit, COMMIT, at=arrived)

The converters never fail on a missing key: catalogs are hand-written and sparse.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any, TypeVar

from apps.kit.arrivals import Stamp

T = TypeVar("T")
Record = Mapping[str, Any]
Field = Callable[[Record], Any]  # a catalog record → one attribute's value
Fields = Mapping[str, Field]  # attribute → how it is read
# An attribute that needs more than its record: the catalog (display names…), the arrival.
Given = Callable[[Any, Record, Stamp], Any]


def text(key: str, default: str = "") -> Field:
    """The value as text; `default` only when the key is missing."""
    return lambda record: str(record.get(key, default))


def text_or(key: str, default: str = "") -> Field:
    """The value as text; `default` when it is missing or empty (None, "")."""
    return lambda record: str(record.get(key) or default)


def number(key: str) -> Field:
    """The value as an int; 0 when missing or empty."""
    return lambda record: int(record.get(key) or 0)


def flag(key: str) -> Field:
    return lambda record: bool(record.get(key))


def inner(key: str, inner_key: str) -> Field:
    """Text from a nested object (`lastCommit` → `sha`); "" when either is missing."""
    return lambda record: str((record.get(key) or {}).get(inner_key, ""))


def each(key: str, kind: Callable[..., T], fields: Fields) -> Field:
    """A tuple of `kind`, one read from each object of the list at `key`."""
    return lambda record: tuple(read(kind, fields, item) for item in record.get(key) or ())


def read(kind: Callable[..., T], fields: Fields, record: Record, **known: Any) -> T:
    """A `kind` with every declared attribute read from `record`; `known` ones as given."""
    return kind(**{name: get(record) for name, get in fields.items()}, **known)


def reader(
    environment: str, table: str, kind: Callable[..., T], fields: Fields, **given: Given
) -> Callable[[Any, str, Stamp], T | None]:
    """`make(state, id, stamp)`: the `kind` read from row `id` of the catalog's `table` (its
    `id` the row's), the attributes in `given` computed from the catalog, row and stamp; None
    for an id the table does not have."""

    def make(state: Any, record_id: str, stamp: Stamp) -> T | None:
        catalog = state.catalog
        record = catalog.table(environment, table).get(record_id)
        if record is None:
            return None
        computed = {name: get(catalog, record, stamp) for name, get in given.items()}
        return read(kind, fields, record, id=record_id, **computed)

    return make
