"""What a run's log may hold, entry by entry, as payload schemas: `logged_schema(environment,
kind, type)`.

Scenario events and actions have their environment's schemas (`EventType.schema`,
`Action.schema`); an action is logged as its `decide` returned it, which may add what it decided
(a generated id), so its logged form takes fields beyond its schema's. What the engine itself
logs — a run's lifecycle entries and its page views — has the schemas below.

The live doors write lifecycle entries and views themselves, so only two places read these: the
contact door holds an agent's message to `ContactPost` (free text, bounded as every other free
text an agent writes: apps/kit/fields.py), and an import holds every line of a file to
`logged_schema` (apps/replay/transfer.py), since a file can say anything.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from types import MappingProxyType
from typing import Annotated, Any, Literal

from pydantic import ConfigDict, Field, StringConstraints

from apps.kit.fields import Text
from events.commands import VIEW_PATH_LIMIT
from events.fastforward import SKIP
from events.lifecycle import CONTACT_GET, CONTACT_POST
from events.models import EventKind
from events.registry import EMPTY, Environment
from events.schemas import Payload

# Spelled out for the type checker; a test holds them to the engine's own (ClockMode, and the
# `why` of events.fastforward).
ClockModeName = Literal["live", "virtual", "fast_forward"]
SkipReason = Literal["slept", "change", "timeout", "kill_at"]


class Nothing(Payload):
    """An entry that says everything by its type: `advance`, `close`, a contact by GET."""


class Init(Payload):
    speed_factor: float
    clock_mode: ClockModeName


class Start(Payload):
    started_at: float = Field(description="the wall time (Unix seconds) of simulated second 0")


class ContactPost(Payload):
    """The contact form: what the agent says it found or did."""

    message: Text


class Skip(Payload):
    """A fast-forward wait: the clock skipped from `from` to `to` (simulated seconds)."""

    from_: float = Field(alias="from")
    to: float
    why: SkipReason


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


@functools.cache
def as_logged(schema: type[Payload]) -> type[Payload]:
    """`schema` as its action is logged: every field it declares, checked as the live door checks
    it, and whatever its `decide` added beside them (storable, as every payload must be)."""
    return type(
        f"Logged{schema.__name__}",
        (schema,),
        {"model_config": ConfigDict(extra="allow"), "__module__": schema.__module__},
    )


def logged_schema(environment: Environment[Any], kind: str, type_: str) -> type[Payload] | None:
    """The schema of an entry of `kind` and `type_` in a run of `environment`; None when no
    door of this server logs such an entry."""
    if kind == EventKind.SCENARIO:
        event_type = environment.event_types.get(type_)
        return event_type.schema if event_type else None
    if kind == EventKind.ACTION:
        action = environment.actions.get(type_)
        return as_logged(action.schema) if action else None
    return _ENGINES.get(kind, EMPTY).get(type_)


_ENGINES: Mapping[str, Mapping[str, type[Payload]]] = {
    EventKind.LIFECYCLE: LIFECYCLE,
    EventKind.VIEW: VIEWS,
}


def logged_types(environment: Environment[Any], kind: str) -> list[str]:
    """The entry types of `kind` a run of `environment` may log."""
    if kind == EventKind.SCENARIO:
        return sorted(environment.event_types)
    if kind == EventKind.ACTION:
        return sorted(environment.actions)
    return sorted(_ENGINES.get(kind, EMPTY))
