"""What every environment's state is built from, and how the next state is built.

A state is a frozen dataclass on `CatalogState` (or `SelfUserState`, when its pages show the
catalog's self user) whose collections are read-only mappings (id → record); reducers return a
changed copy and never fail on replay (an id that is gone, or never arrived, changes nothing):

    with_items(mail, "emails", [(email.id, email)])          add or replace records
    with_changed(mail, "states", email_id, is_read=True)      change fields of one record
    without(mail, email_id, "emails", "states")               take an item out for good
    setting("states", "email_id", is_read=True)               a reducer doing with_changed

Copying a dict of a few hundred entries is cheap next to rendering, and it keeps every folded
state a value: the fold cache, kept screens and time travel can hold on to it safely.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, ClassVar, Self, TypeVar

from events.registry import LoggedEvent, Reducer

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


def with_items_first(state: S, field: str, items: Iterable[tuple[Any, Any]]) -> S:
    """`with_items`, the new entries placed before those already there (a list the newest item
    heads); an entry already there keeps its place and is replaced."""
    items = [(key, value) for key, value in items]
    if not items:
        return state
    current = getattr(state, field)
    new = {key: value for key, value in items if key not in current}
    merged = {**new, **current}
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


def without(state: S, key: Any, *fields: str) -> S:
    """`state` with the entry `key` taken out of each of its mappings `fields`."""
    changes = {
        field: MappingProxyType({k: v for k, v in mapping.items() if k != key})
        for field in fields
        if key in (mapping := getattr(state, field))
    }
    return replace(state, **changes) if changes else state


def setting(field: str, key: str, **changes: Any) -> Reducer[S]:
    """A reducer setting `changes` on the record the logged payload's `key` names."""

    def reduce(state: S, event: LoggedEvent) -> S:
        return with_changed(state, field, event.payload[key], **changes)

    reduce.__doc__ = f"Set {', '.join(f'{k}={v!r}' for k, v in changes.items())} on {field}[{key}]."
    return reduce


@dataclass(frozen=True)
class SelfUserState(CatalogState):
    """A state whose pages know who "me" is: the catalog's self user, an input like the catalog,
    with the environment's `FALLBACK` when the catalog names nobody.

        @dataclass(frozen=True)
        class Agenda(SelfUserState):
            FALLBACK: ClassVar[Mapping[str, str]] = MappingProxyType({"name": "Me", …})

        empty_agenda = Agenda.of  # catalog → the empty state, its self user in place
    """

    # Left out of equality and repr, like the catalog it comes from.
    self_user: Mapping[str, Any] = field(
        compare=False, repr=False, default_factory=lambda: MappingProxyType({})
    )
    # What a page shows when the catalog has no self user (or a record without the field).
    FALLBACK: ClassVar[Mapping[str, str]] = MappingProxyType({})

    @classmethod
    def of(cls, catalog: Any) -> Self:
        """The empty state of `catalog`, with its self user."""
        return cls(catalog=catalog, self_user=getattr(catalog, "self_user", None) or cls.FALLBACK)

    def me(self, key: str) -> str:
        """The self user's `key` ("name", "email", "id"), else the fallback's."""
        return str(self.self_user.get(key) or self.FALLBACK[key])

    @property
    def self_name(self) -> str:
        return self.me("name")

    @property
    def self_email(self) -> str:
        return self.me("email")

    @property
    def self_id(self) -> str:
        return self.me("id")
