"""Actions that set flags on one item (save / unsave, mark read, delete as a flag): the shape
every environment wrote out action by action — same payload, same check, `setting(...)`.

    marks = marking(PaperId, decide_on_paper, "paper_states", "paper_id", page=paper_page)
    ACTIONS = {"save": marks(saved=True, help="Add a paper to My library."), …}
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from apps.kit.state import setting
from events.registry import Action, PageStep
from events.schemas import Payload


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
