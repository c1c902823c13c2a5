"""The plug-in interface between the core and the environments.

An environment app builds one `Environment` and calls `register()` from its AppConfig.ready().
The core only ever talks to environments through this module.
"""

from __future__ import annotations

import sqlite3
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, NamedTuple

State = Any  # each environment defines its own immutable state type


class LoggedEvent(NamedTuple):
    """What reducers see of a logged event: light, immutable, independent of the ORM."""

    seq: int
    at: float
    kind: str
    type: str
    payload: Mapping[str, Any]


class PayloadError(ValueError):
    """A scenario-event or action payload does not match its schema."""


class ActionRejected(ValueError):
    """An agent action is not allowed against the current state (e.g. unknown email id)."""

    def __init__(self, message: str, status: int = 400):
        super().__init__(message)
        self.status = status


Reducer = Callable[[State, LoggedEvent], State]


@dataclass(frozen=True)
class Field:
    """One payload field: its type and whether it may be omitted.

    A deliberately small schema language: enough to give authors precise errors (field,
    expected type, allowed values) without pulling in a JSON-Schema dependency.
    """

    type: type | tuple[type, ...]
    required: bool = True
    choices: tuple[Any, ...] | None = None
    help: str = ""

    def describe(self) -> str:
        names = self.type if isinstance(self.type, tuple) else (self.type,)
        text = " or ".join(_TYPE_NAMES.get(t, t.__name__) for t in names)
        if self.choices:
            text += f" (one of: {', '.join(map(str, self.choices))})"
        return text


_TYPE_NAMES = {str: "string", int: "integer", float: "number", bool: "boolean", list: "list", dict: "object"}


def validate_payload(schema: Mapping[str, Field], payload: Any, *, what: str) -> dict:
    if not isinstance(payload, dict):
        raise PayloadError(f"{what}: payload must be an object, got {type(payload).__name__}")
    for name, spec in schema.items():
        if name not in payload:
            if spec.required:
                raise PayloadError(f"{what}: payload field '{name}' is required ({spec.describe()})")
            continue
        value = payload[name]
        expected = spec.type if isinstance(spec.type, tuple) else (spec.type,)
        ok = isinstance(value, expected) and not (isinstance(value, bool) and bool not in expected)
        if float in expected and isinstance(value, int) and not isinstance(value, bool):
            ok = True
        if not ok:
            raise PayloadError(f"{what}: payload field '{name}' must be {spec.describe()}, got {value!r}")
        if spec.choices is not None and value not in spec.choices:
            raise PayloadError(
                f"{what}: payload field '{name}' is {value!r}; allowed: {', '.join(map(str, spec.choices))}"
            )
    unknown = sorted(set(payload) - set(schema))
    if unknown:
        raise PayloadError(
            f"{what}: unknown payload field(s) {', '.join(unknown)}; allowed: {', '.join(schema) or 'none'}"
        )
    return payload


@dataclass(frozen=True)
class EventType:
    """A scenario event type: its payload schema and the reducer that applies it."""

    schema: Mapping[str, Field]
    reduce: Reducer
    help: str = ""
    # Catalog references to check when a scenario is authored: payload field → (catalog
    # table); a list field may be ["*"].
    catalog_refs: Mapping[str, str] = field(default_factory=dict)


@dataclass(frozen=True)
class Action:
    """An agent action: validated against the current state by `decide`, then logged.

    `decide(state, payload)` returns the payload to record (it may add derived fields, e.g.
    a generated id) or raises ActionRejected. It never mutates anything.
    """

    schema: Mapping[str, Field]
    decide: Callable[[State, dict], dict]
    reduce: Reducer
    help: str = ""


@dataclass
class Environment:
    """Everything the core needs to know about one environment."""

    name: str
    title: str
    initial_state: Callable[[Any], State]  # catalog → empty state
    event_types: Mapping[str, EventType]
    actions: Mapping[str, Action]
    baselines: Callable[[State], Mapping[str, float | int]]
    materialize: Callable[[State, sqlite3.Connection], None]
    urlconf: str | None = None  # module with the environment's page urlpatterns
    # Name → catalog table used to expand ["*"] in preload payloads (for authoring checks).
    catalog_tables: tuple[str, ...] = ()
    # state → every kind of page worth timing, as paths relative to the environment root
    # (e.g. "?folder=inbox"); used by `manage.py bench_pages`.
    sample_pages: Callable[[State], list[str]] | None = None

    def apply(self, state: State, event: LoggedEvent) -> State:
        """Apply one logged event. Views and lifecycle events never change environment state."""
        if event.kind == "scenario":
            event_type = self.event_types.get(event.type)
            # Unknown types are ignored, as upstream does (its tests use type "noop").
            return event_type.reduce(state, event) if event_type else state
        if event.kind == "action":
            action = self.actions.get(event.type)
            return action.reduce(state, event) if action else state
        return state

    def fold(self, state: State, events) -> State:
        apply = self.apply
        for event in events:
            state = apply(state, event)
        return state


_REGISTRY: dict[str, Environment] = {}


def register(environment: Environment) -> Environment:
    existing = _REGISTRY.get(environment.name)
    if existing is not None and existing is not environment:
        raise ValueError(f"environment {environment.name!r} is registered twice")
    _REGISTRY[environment.name] = environment
    return environment


def unregister(name: str) -> None:
    _REGISTRY.pop(name, None)


class UnknownEnvironment(LookupError):
    def __init__(self, name: str):
        super().__init__(
            f"unknown environment {name!r}; valid: {', '.join(environment_names()) or 'none registered'}"
        )


def get_environment(name: str) -> Environment:
    try:
        return _REGISTRY[name]
    except KeyError:
        raise UnknownEnvironment(name) from None


def environment_names() -> list[str]:
    return sorted(_REGISTRY)


def all_environments() -> list[Environment]:
    return [_REGISTRY[name] for name in sorted(_REGISTRY)]
