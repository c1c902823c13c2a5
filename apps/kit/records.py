"""Catalog records (plain JSON objects) read into frozen dataclasses whose fields declare them.

A record type declares once, on each field the catalog has, which key it comes from and how it
is converted (`from_catalog(text("sha"))`); one generic `read` builds the value, and `reader`
makes the `make(state, id, stamp)` of an `arrivals.Delivery` from a catalog table:

    @dataclass(frozen=True)
    class Check:
        name: str = from_catalog(text("name"))
        status: str = from_catalog(text_or("status", "pending"))

    checks: tuple[Check, ...] = from_catalog(each("checks", Check), default=())
    commit = reader("microhub", "commits", Commit, at=arrived)  # `at` computed, not read

The converters never fail on a missing key: catalogs are hand-written and sparse.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping
from typing import Any, TypeVar

from apps.kit.arrivals import Stamp
from apps.kit.feeds import from_catalog as from_table
from apps.kit.streaming import whole

T = TypeVar("T")
Record = Mapping[str, Any]
Field = Callable[[Record], Any]  # a catalog record → one attribute's value
# An attribute that needs more than its record: the catalog (display names…), the arrival.
Given = Callable[[Any, Record, Stamp], Any]


def from_catalog(get: Field, **options: Any) -> Any:
    """A dataclass field read from a catalog record by `get`; `options` as for `field()`."""
    return dataclasses.field(metadata={"catalog": get}, **options)


def declared(kind: Any) -> Mapping[str, Field]:
    """attribute → how it is read, for each field of `kind` declared `from_catalog`."""
    return {
        f.name: f.metadata["catalog"] for f in dataclasses.fields(kind) if "catalog" in f.metadata
    }


def text(key: str, default: str = "") -> Field:
    """The value as text; `default` only when the key is missing."""
    return lambda record: str(record.get(key, default))


def text_or(key: str, default: str = "") -> Field:
    """The value as text; `default` when it is missing or empty (None, "")."""
    return lambda record: str(record.get(key) or default)


def integer(key: str) -> Field:
    """The value as an int; 0 when missing or empty."""
    return lambda record: int(record.get(key) or 0)


def raw(key: str) -> Field:
    """The value as the catalog gives it, unconverted; None when missing."""
    return lambda record: record.get(key)


def texts(key: str) -> Field:
    """A list's items as texts; () when the value is not a list."""
    return lambda record: tuple(map(str, v)) if isinstance(v := record.get(key), list) else ()


def flag(key: str) -> Field:
    return lambda record: bool(record.get(key))


def inner(key: str, inner_key: str) -> Field:
    """Text from a nested object (`lastCommit` → `sha`); "" when either is missing."""
    return lambda record: str((record.get(key) or {}).get(inner_key, ""))


def each(key: str, kind: type[T]) -> Field:
    """A tuple of `kind`, one read from each object of the list at `key`."""
    return lambda record: tuple(read(kind, item) for item in record.get(key) or ())


def read(kind: type[T], record: Record, **known: Any) -> T:
    """A `kind` with every declared attribute read from `record`; `known` ones as given."""
    return kind(**{name: get(record) for name, get in declared(kind).items()}, **known)


def reader(
    environment: str, table: str, kind: type[T], **given: Given
) -> Callable[[Any, str, Stamp], T | None]:
    """`make(state, id, stamp)`: the `kind` read from row `id` of the catalog's `table` (its
    `id` the row's), the attributes in `given` computed from the catalog, row and stamp; None
    for an id the table does not have."""

    @from_table(environment, table)
    def make(state: Any, record_id: str, record: Record, stamp: Stamp) -> T:
        computed = {name: get(state.catalog, record, stamp) for name, get in given.items()}
        return read(kind, record, id=record_id, **computed)

    return make


def whole_number(key: str, default: int = 0) -> Field:
    """A catalog number as an int, forgiving (`streaming.whole`): `"1200"` or `1200`; `default`
    when it is missing or garbled."""
    return lambda record: whole(record.get(key), default)
