"""Building the next immutable state: every environment's state is a frozen dataclass whose
collections are read-only mappings (id → record), and reducers return a changed copy.

    with_items(mail, "emails", [(email.id, email)])          add or replace records
    with_changed(mail, "states", email_id, is_read=True)      change fields of one record

Copying a dict of a few hundred entries is cheap next to rendering, and it keeps every folded
state a value: the fold cache, kept screens and time travel can hold on to it safely.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, TypeVar

if TYPE_CHECKING:
    from _typeshed import DataclassInstance

EMPTY: Mapping = MappingProxyType({})

# A state: a (frozen) dataclass, which `replace` copies. What is generic in a state imports it.
S = TypeVar("S", bound="DataclassInstance")


def with_items(state: S, field: str, items: Iterable[tuple[Any, Any]]) -> S:
    """`state` with the entries `items` added to (or replacing those in) its mapping `field`;
    entries already there keep their place. No items: `state` itself."""
    items = list(items)
    if not items:
        return state
    merged = dict(getattr(state, field))
    merged.update(items)
    return replace(state, **{field: MappingProxyType(merged)})


def with_changed(state: S, field: str, key: Any, **changes: Any) -> S:
    """`state` with fields of the record `field[key]` changed; a key that is not there (gone,
    never arrived) leaves `state` as it is — a reducer never fails on replay."""
    current = getattr(state, field).get(key)
    if current is None:
        return state
    return with_items(state, field, [(key, replace(current, **changes))])


@dataclass(frozen=True)
class CatalogState:
    """The base of every environment's state: the catalog it is built from.

    The catalog is an input, not state: it is left out of equality and `repr`, so two folds of
    the same log compare equal cheaply (comparing would canonicalise the whole catalog) and a
    state prints readably. Subclasses are frozen dataclasses adding their own fields.
    """

    catalog: Any = field(compare=False, repr=False)
