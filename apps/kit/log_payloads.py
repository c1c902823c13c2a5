"""What the engine itself logs besides scenario events and actions — a run's lifecycle entries and
its page views — as payload schemas, entry type by entry type.

The live doors write these entries themselves, so only two places read the schemas: the contact
door holds an agent's message to `ContactPost` (its message is free text, bounded as every other
free text an agent writes: apps/kit/fields.py), and an import holds every such line of a file to
them (apps/replay/transfer.py), since a file can say anything.
"""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType
from typing import Annotated, Literal

from pydantic import Field, StringConstraints

from apps.kit.fields import Text
from events.commands import VIEW_PATH_LIMIT
from events.fastforward import CHANGE, KILL_AT, SKIP, SLEPT, TIMEOUT
from events.lifecycle import CONTACT_GET, CONTACT_POST
from events.models import ClockMode
from events.schemas import Payload

CLOCK_MODES = tuple(ClockMode.values)
SKIP_REASONS = (SLEPT, CHANGE, TIMEOUT, KILL_AT)


class Nothing(Payload):
    """An entry that says everything by its type: `advance`, `close`, a contact by GET."""


class Init(Payload):
    speed_factor: float
    clock_mode: Literal[CLOCK_MODES]


class Start(Payload):
    started_at: float = Field(description="the wall time (Unix seconds) of simulated second 0")


class ContactPost(Payload):
    """The contact form: what the agent says it found or did."""

    message: Text


class Skip(Payload):
    """A fast-forward wait: the clock skipped from `from` to `to` (simulated seconds)."""

    from_: float = Field(alias="from")
    to: float
    why: Literal[SKIP_REASONS]


LIFECYCLE: Mapping[str, type[Payload]] = MappingProxyType(
    {
        "init": Init,
        "start": Start,
        "advance": Nothing,
        CONTACT_GET: Nothing,
        CONTACT_POST: ContactPost,
        SKIP: Skip,
        "close": Nothing,
    }
)


class PageView(Payload):
    path: Annotated[str, StringConstraints(max_length=VIEW_PATH_LIMIT)]
    partial: bool = False  # an htmx request for part of a page
    path_length: int | None = Field(None, description="the whole URL's length, when cut")


VIEWS: Mapping[str, type[Payload]] = MappingProxyType({"page": PageView})
