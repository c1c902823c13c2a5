"""Taking an item out of a state for good (a purged email, a deleted message), with everything
kept beside it under the same id: its per-item state, its reactions…

    without(mail, email_id, "emails", "states")

The companion of `apps.kit.frozen.with_items`: a reducer returns a changed copy and never fails
on replay, so an id that is not there (gone already, never arrived) leaves the state as it is.
"""

from __future__ import annotations

from dataclasses import replace
from types import MappingProxyType
from typing import Any, TypeVar

S = TypeVar("S")


def without(state: S, key: Any, *fields: str) -> S:
    """`state` with the entry `key` taken out of each of its mappings `fields`."""
    changes = {
        field: MappingProxyType({k: v for k, v in mapping.items() if k != key})
        for field in fields
        if key in (mapping := getattr(state, field))
    }
    return replace(state, **changes) if changes else state
