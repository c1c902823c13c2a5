"""The action a page performs by being opened, declared in one line: opening an unread email
marks it read, opening a chat reads it, opening a video watches it.

    implicit_actions=(opening("mailbox", "email", "open_email", "email_id", applies=unread),)

is `ImplicitAction(page="mailbox", param="email", action="open_email",
payload=lambda email_id: {"email_id": email_id}, applies=unread)`: the id the URL carries is the
one field of the action's payload.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

from events.registry import ImplicitAction

S = TypeVar("S")


def opening(
    page: str, param: str, action: str, field: str, *, applies: Callable[[S, str], bool]
) -> ImplicitAction[S]:
    """Opening the page named `page` with `param=<id>` performs `action {field: id}`, when
    `applies(state, id)` (so that reloading the page changes nothing)."""

    def payload(item_id: str) -> dict[str, Any]:
        return {field: item_id}

    return ImplicitAction(page=page, param=param, action=action, payload=payload, applies=applies)
