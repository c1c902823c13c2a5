"""Items that go away at their time: a message its sender deletes, a mail recalled, an event its
organiser cancels, a job closed to applications, a pull request someone else closed.

A retraction is the mirror of an arrival (`apps.kit.arrivals`): the event `name {field: id}`
marks one item of the state's mapping `items` gone *now*. The item is not taken out: pages
show what the real product shows in its place (Teams' "This message has been deleted.") or hide
it, and the grading database keeps it, with when it appeared and when it went away, so a
scenario's `eval_sql` can require that the agent acted while it was there.

    retraction("unsend_message", "message_id", "messages", "messages",
               help="The sender deletes one of their messages.")

The item's dataclass carries `gone_at: float | None = None`; `window(appeared)` gives an
evaluation table its two columns:

    Table("messages", …, {…, **window("sent_at")})   # appeared_at REAL, gone_at REAL

A retraction of an item not there (never arrived, a typo the validation reports) or already
gone changes nothing: the first retraction is the one that counts, and replay never fails.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any, TypeVar

from apps.kit.arrivals import id_payload
from apps.kit.state import S, with_changed
from apps.kit.tables import Getter
from events.registry import EventType, LoggedEvent

T = TypeVar("T")


def retraction(
    name: str,
    field: str,
    table: str | None,
    items: str,
    *,
    help: str,
    description: str | None = None,
) -> tuple[str, EventType[S]]:
    """The event `name {field: id}`: the item `id` of the state's mapping `items` goes away
    now. `table` is the catalog table the id is checked against (None: no single table)."""

    def reduce(state: S, event: LoggedEvent) -> S:
        item_id = event.payload[field]
        item = getattr(state, items).get(item_id)
        if item is None or item.gone_at is not None:
            return state
        return with_changed(state, items, item_id, gone_at=event.at)

    reduce.__doc__ = help
    schema = id_payload(name, field, description)
    refs = {field: table} if table else {}
    return name, EventType(schema=schema, reduce=reduce, help=help, catalog_refs=refs)


def present(items: Iterable[T]) -> list[T]:
    """The items not gone: what a list, a count or a badge shows."""
    return [item for item in items if getattr(item, "gone_at", None) is None]


def is_gone(item: Any) -> bool:
    return getattr(item, "gone_at", None) is not None


def still_there(items: Mapping[str, Any], item_id: str) -> bool:
    """`items` holds `item_id` and it has not gone: what opening its page can act on (a story
    that expired or a video made private plays nothing, so opening it watches nothing)."""
    item = items.get(item_id)
    return item is not None and not is_gone(item)


def window(appeared: Getter) -> Mapping[str, Getter]:
    """An evaluation table's columns for when each item was there: `appeared_at` (read by
    `appeared`, an attribute name or a function of the row) and `gone_at` (NULL while it
    is still there)."""
    return {"appeared_at REAL": appeared, "gone_at REAL": "gone_at"}
