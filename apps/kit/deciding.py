"""What every environment's actions need: a fresh id, a required text, an existing item — and
the two kinds of action declared whole (`marking`: set flags on one item; `opening`: what a page
does by being opened).

decide() is where an action is refused (`ActionRejected`, whose status the API answers with) and
where anything the log must remember is chosen. These helpers read the state and never change it.

    marks = marking(PaperId, decide_on_paper, "paper_states", "paper_id", page=paper_page)
    ACTIONS = {"save": marks(saved=True, help="Add a paper to My library."), …}
    IMPLICIT_ACTIONS = (opening("mailbox", "email", "open_email", "email_id", applies=unread),)
"""

from __future__ import annotations

import uuid
from collections.abc import Callable, Mapping
from typing import Any, TypeVar

from apps.kit.retractions import is_gone
from apps.kit.state import setting
from events.registry import Action, ActionRejected, ImplicitAction, PageStep
from events.schemas import Payload

Item = TypeVar("Item")
S = TypeVar("S")


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
    if item is None or is_gone(item):  # gone (apps.kit.retractions): there is nothing to act on
        raise ActionRejected(f"no {what} {item_id!r} {where}", status=404)
    return item


def checking(field: str, key: str, what: str, where: str) -> Callable[[Any, dict], dict]:
    """A decide() for an action whose only rule is that its item is there: `payload[key]` among
    `state.<field>` (a like, a mark-read). The payload is logged as it came."""

    def decide(state: Any, payload: dict) -> dict:
        found(getattr(state, field), payload[key], what, where)
        return payload

    return decide


def marking(
    schema: type[Payload],
    decide: Callable[..., dict],
    field: str,
    key: str,
    *,
    page: Callable[[Any, dict], PageStep] | None = None,
) -> Callable[..., Action]:
    """`marks(help=…, **flags)`: an Action on `schema` checked by `decide` that sets `flags` on
    `state.<field>[payload[key]]` (set, not toggled: a repeated request changes nothing), done on
    `page` unless the action names its own."""

    def marks(*, help: str = "", page: Any = page, **flags: Any) -> Action:
        return Action(schema, decide, setting(field, key, **flags), help=help, page=page)

    return marks


def opening(
    page: str, param: str, action: str, field: str, *, applies: Callable[[S, str], bool]
) -> ImplicitAction[S]:
    """Opening the page named `page` with `param=<id>` performs `action {field: id}`, when
    `applies(state, id)` (so that reloading the page changes nothing)."""

    def payload(item_id: str) -> dict[str, Any]:
        return {field: item_id}

    return ImplicitAction(page=page, param=param, action=action, payload=payload, applies=applies)
