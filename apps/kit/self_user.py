"""A state that knows who "me" is: the catalog's self user (name, email, id), an input like the
catalog itself, with the environment's fallback when the catalog names nobody.

    @dataclass(frozen=True)
    class Agenda(SelfUserState):
        FALLBACK: ClassVar[Mapping[str, str]] = MappingProxyType({"name": "Me", "email": "me@…"})
        events: …

    empty_agenda = Agenda.of  # catalog → the empty state, its self user in place
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any, ClassVar, Self

from apps.kit.frozen import CatalogState


@dataclass(frozen=True)
class SelfUserState(CatalogState):
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
