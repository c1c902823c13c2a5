"""The plug-in interface between the core and the environments.

An environment app builds one `Environment` and calls `register()` from its AppConfig.ready().
The core only ever talks to environments through this module.
"""

from __future__ import annotations

import sqlite3
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any, Generic, NamedTuple, TypeVar

from events.schemas import Payload, PayloadError, validate_payload

# Each environment defines its own immutable state type; the interface is generic in it, so a
# type checker sees that an environment's reducers, decisions and measures agree on one state.
S = TypeVar("S")


class LoggedEvent(NamedTuple):
    """What reducers see of a logged event: light, immutable, independent of the ORM."""

    seq: int
    at: float
    kind: str
    type: str
    payload: Mapping[str, Any]


class ActionRejected(ValueError):
    """An agent action is not allowed against the current state (e.g. unknown email id)."""

    def __init__(self, message: str, status: int = 400):
        super().__init__(message)
        self.status = status


Reducer = Callable[[S, LoggedEvent], S]


@dataclass(frozen=True)
class EventType(Generic[S]):
    """A scenario event type: its payload schema and the reducer that applies it."""

    schema: type[Payload]
    reduce: Reducer[S]
    help: str = ""
    # Catalog references to check when a scenario is authored: payload field → (catalog
    # table); a list field may be ["*"].
    catalog_refs: Mapping[str, str] = field(default_factory=dict)
    # A preload puts the world the task starts from in place. Right after one applies, the core
    # measures the environment's baselines (the original's rule: the last preload wins, and
    # without one there are none).
    preload: bool = False


@dataclass(frozen=True)
class PageStep:
    """How a person performs an action through the pages: open `path` (relative to the
    environment root, e.g. "?folder=inbox&email=x"); then, unless `form` is None, submit the
    form (or submit button) marked `data-action="<action name>"` on that page with these field
    values. With `form=None`, opening the page is the action (an implicit one)."""

    path: str
    form: Mapping[str, str | list[str]] | None = None


@dataclass(frozen=True)
class Action(Generic[S]):
    """An agent action: validated against the current state by `decide`, then logged.

    `decide(state, payload)` returns the payload to record (it may add derived fields, e.g.
    a generated id) or raises ActionRejected. It never mutates anything. `page(state, payload)`
    says where a person does it in the site (the generic tests carry out every scenario's
    solution that way, through forms and links).
    """

    schema: type[Payload]
    decide: Callable[..., dict]  # (state, payload) → payload, or (state, payload, now) if timed
    reduce: Reducer[S]
    help: str = ""
    page: Callable[[S, dict], PageStep] | None = None
    # The decision depends on the clock (a market order is checked against the price of its
    # moment): then `decide(state, payload, now)`, `now` being the simulated second it is logged at.
    timed: bool = False

    def decide_at(self, state: S, payload: dict, now: float) -> dict:
        """`decide`, given the moment when the action says it needs one (`timed`)."""
        return self.decide(state, payload, now) if self.timed else self.decide(state, payload)


@dataclass(frozen=True)
class ImplicitAction(Generic[S]):
    """An action a page performs by being opened, as the real product does: opening an unread
    message marks it read. Declared with the environment so no view has to remember it.

    On a navigation (not a live re-render, not time travel) to the page named `page` (its URL
    name) whose query string or URL carries `param`, the core performs `action` with
    `payload(value)` — but only when `applies(state, value)`, so reloading changes nothing.
    """

    page: str
    param: str
    action: str
    payload: Callable[[str], dict]
    applies: Callable[[S, str], bool]


Measure = Callable[[S, float], float | int]  # (state, now) → a number
EMPTY: Mapping[str, Any] = MappingProxyType({})


def timeless(count: Callable[[S], float | int]) -> Measure[S]:
    """A baseline that depends on the state only (most counts do) as a `measure(state, now)`."""
    return lambda state, now: count(state)


def counted(counts: Mapping[str, Callable[[S], float | int]]) -> Mapping[str, Measure[S]]:
    """Baselines that are counts of the state alone: `{"unread_count": unread_count, …}`."""
    return MappingProxyType({name: timeless(count) for name, count in counts.items()})


class Performed(NamedTuple, Generic[S]):
    """An action carried out on a state: what is logged, and the state once it is applied."""

    payload: dict  # as decided (with any derived field, e.g. a generated id): the logged payload
    state: S  # the state with the action applied, as the next fold will give it


@dataclass(frozen=True)
class Environment(Generic[S]):
    """Everything the core needs to know about one environment.

    Time reaches the environment explicitly: `now` is the simulated second (authored scale) of
    the operation, read once from the run's clock. Values that move between events (a price, a
    star count) are functions of the state and `now` (apps.kit.waypoints), never events of their own.
    """

    name: str
    title: str
    initial_state: Callable[[Any], S]  # catalog → the empty state
    event_types: Mapping[str, EventType[S]]
    actions: Mapping[str, Action[S]]
    # name → measure(state, now); captured by the core right after each preload applies, and
    # exported to eval_sql as session_meta rows `baseline_<name>`.
    baselines: Mapping[str, Measure[S]]
    # The evaluation tables as of `now` (upstream names and columns, so eval_sql runs unchanged).
    materialize: Callable[[S, float, sqlite3.Connection], None]
    urlconf: str | None = None  # module with the environment's page urlpatterns
    implicit_actions: tuple[ImplicitAction[S], ...] = ()
    # state → every kind of page worth timing, as paths relative to the environment root
    # (e.g. "?folder=inbox"); used by `manage.py bench_pages`.
    sample_pages: Callable[[S], list[str]] | None = None
    # The numbers the pages show in more than one place, each with its one value (the kit's
    # apps.kit.counts.ShownCount): the generic tests check every sample page agrees with it.
    shown_counts: tuple[Any, ...] = ()

    def action(self, name: str) -> Action[S]:
        """The action called `name`, or a refusal naming the ones there are."""
        found = self.actions.get(name)
        if found is None:
            raise ActionRejected(
                f"unknown action {name!r} for {self.name}; allowed: {', '.join(sorted(self.actions))}",
                status=400,  # the request names no such thing: a bad request, not a missing page
            )
        return found

    def perform(self, state: S, name: str, payload: Mapping[str, Any], at: float) -> Performed[S]:
        """Carry out action `name` on `state` at simulated second `at`, purely: validate the
        payload, decide (ActionRejected when the state does not allow it) and apply the event
        that would be logged. The server logs `payload` and keeps `state`; tests call it alone."""
        action = self.action(name)
        try:
            validate_payload(action.schema, payload, what=f"action {name}")
        except PayloadError as exc:
            raise ActionRejected(str(exc)) from None
        decided = action.decide_at(state, dict(payload), at)
        # seq is unknown until logged: no reducer reads it (they see payload and time only).
        event = LoggedEvent(seq=0, at=at, kind="action", type=name, payload=decided)
        return Performed(decided, action.reduce(state, event))

    def apply(self, state: S, event: LoggedEvent) -> S:
        """Apply one logged event. Views and lifecycle events never change environment state."""
        if event.kind == "scenario":
            event_type = self.event_types.get(event.type)
            # Unknown types are ignored, as upstream does (its tests use type "noop").
            return event_type.reduce(state, event) if event_type else state
        if event.kind == "action":
            action = self.actions.get(event.type)
            return action.reduce(state, event) if action else state
        return state

    def measure_baselines(self, state: S, now: float) -> Mapping[str, float | int]:
        return MappingProxyType(
            {name: measure(state, now) for name, measure in self.baselines.items()}
        )

    def captures_baselines(self, event: LoggedEvent) -> bool:
        event_type = self.event_types.get(event.type) if event.kind == "scenario" else None
        return event_type is not None and event_type.preload

    def fold(
        self, state: S, events, baselines: Mapping[str, Any] = EMPTY
    ) -> tuple[S, Mapping[str, Any]]:
        """Apply `events` in order; baselines are measured right after every preload."""
        apply, captures = self.apply, self.captures_baselines
        for event in events:
            state = apply(state, event)
            if captures(event):
                baselines = self.measure_baselines(state, event.at)
        return state, baselines


_REGISTRY: dict[str, Environment[Any]] = {}


def register(environment: Environment[S]) -> Environment[S]:
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


def get_environment(name: str) -> Environment[Any]:
    try:
        return _REGISTRY[name]
    except KeyError:
        raise UnknownEnvironment(name) from None


def environment_names() -> list[str]:
    return sorted(_REGISTRY)


def all_environments() -> list[Environment[Any]]:
    return [_REGISTRY[name] for name in sorted(_REGISTRY)]
