"""Reducers that set fields of one record: the shape of most small actions (mark read, like,
save, delete), declared instead of written out.

    "cite": Action(PaperId, decide_on_paper, setting("paper_states", "paper_id", cited=True))

The record is `state.<field>[payload[key]]`; an id that is not there (gone, never arrived)
leaves the state as it is (apps.kit.frozen.with_changed), so replay never fails.
"""

from __future__ import annotations

from typing import Any, TypeVar

from apps.kit.frozen import with_changed
from events.registry import LoggedEvent, Reducer

S = TypeVar("S")


def setting(field: str, key: str, **changes: Any) -> Reducer[S]:
    """A reducer setting `changes` on the record the logged payload's `key` names."""

    def reduce(state: S, event: LoggedEvent) -> S:
        return with_changed(state, field, event.payload[key], **changes)

    reduce.__doc__ = f"Set {', '.join(f'{k}={v!r}' for k, v in changes.items())} on {field}[{key}]."
    return reduce
