"""What every environment's `Action.decide` needs: a fresh id, a required text, an existing item.

decide() is where an action is refused (`ActionRejected`, whose status the API answers with) and
where anything the log must remember is chosen. These helpers read the state and never change it.
"""

from __future__ import annotations

import uuid
from collections.abc import Callable, Mapping
from typing import Any, TypeVar

from events.registry import ActionRejected

Item = TypeVar("Item")


def new_id(prefix: str) -> str:
    """An id for what the action creates: chosen once in decide() and logged, so replay reuses
    it (a reducer that drew its own would make every fold of the log different)."""
    return f"{prefix}-{uuid.uuid4().hex[:12]}"


def required_text(payload: Mapping[str, Any], key: str) -> str:
    """`payload[key]` without surrounding blanks; a 400 when nothing is left."""
    text = str(payload.get(key) or "").strip()
    if not text:
        raise ActionRejected(f"payload field {key!r} is empty: write something first")
    return text


def found(items: Mapping[str, Item], item_id: str, what: str, where: str) -> Item:
    """`items[item_id]`, or a 404 "no <what> '<id>' <where>". Unknown and not-yet-arrived ids look
    the same, so an agent cannot learn from a refusal what the scenario has in store."""
    item = items.get(item_id)
    if item is None:
        raise ActionRejected(f"no {what} {item_id!r} {where}", status=404)
    return item


def checking(field: str, key: str, what: str, where: str) -> Callable[[Any, dict], dict]:
    """A decide() for an action whose only rule is that its item is there: `payload[key]` among
    `state.<field>` (a like, a mark-read). The payload is logged as it came."""

    def decide(state: Any, payload: dict) -> dict:
        found(getattr(state, field), payload[key], what, where)
        return payload

    return decide
