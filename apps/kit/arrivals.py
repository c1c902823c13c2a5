"""Catalog items arriving in a state: declared once, delivered by one step.

Every environment's scenario events are the same two shapes:

- a *preload* puts many catalog items of several tables in place when the task starts
  (`preload_emails {email_ids: [...]}`; `["*"]` = the whole table), and the core measures the
  baselines right after it;
- an *arrival* brings one item now (`new_email {email_id}`).

And every delivery is the same step: the ids not present yet, in order, once each → the catalog
record made into an item stamped with its arrival time → the item and a fresh per-item state
added to the state. An id already present is the same item delivered twice: left as it is (no
duplicate, nothing the user did to it undone). An id missing from the catalog is skipped;
scenario validation reports it to the author before a run ever starts.

    deliver_emails = Delivery("emails", make_email, states="states")
    EVENT_TYPES = event_types(
        preload("preload_emails", {"email_ids": ("emails", deliver_emails)}, help="…",
                required=("email_ids",)),
        arrival("new_email", "email_id", "emails", deliver_emails, help="One message arrives."),
    )

The schema, the catalog references and the reducer of each event are generated from these
declarations, so they cannot disagree.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, Generic, NamedTuple, Protocol

from pydantic import Field, create_model

from apps.kit.state import S, with_items, with_items_first
from events.registry import EventType, LoggedEvent
from events.schemas import Payload


class Stamp(NamedTuple):
    """When and how an item arrives: what `make` needs to date it."""

    at: float  # the event's simulated second
    preloaded: bool  # part of the starting world (dated before `at`, keeps catalog read flags)
    order: int  # its place among the new items of this delivery (0, 1, …)


class Deliver(Protocol[S]):
    """Anything that delivers catalog ids into a state (a `Delivery`, or a function for an
    item that does not fit it, e.g. a message that brings its conversation along)."""

    def __call__(self, state: S, ids: Iterable[str], at: float, *, preloaded: bool) -> S: ...


@dataclass(frozen=True)
class Delivery(Generic[S]):
    """How catalog items of one kind enter the state: the generic delivery step.

    `make(state, id, stamp)` reads the catalog record and returns the item, or `(item,
    item_state)` when the per-item state depends on the record, or None when the catalog has
    no such id. The item goes into the state's mapping field `items` (id → item, delivery
    order); its per-item state into `states` (id → state), `fresh()` when `make` gave none.
    `newest_first`: what arrives goes before what is there (a list the newest item heads, as
    a repository's commits), instead of after it.
    """

    items: str
    make: Callable[[S, str, Stamp], Any]
    states: str | None = None
    fresh: Callable[[], Any] | None = None
    newest_first: bool = False

    def __call__(self, state: S, ids: Iterable[str], at: float, *, preloaded: bool) -> S:
        present = getattr(state, self.items)
        arrivals: list[tuple[Any, Any]] = []
        for item_id in dict.fromkeys(ids):  # once each, in order
            if item_id in present:
                continue
            made = self.make(state, item_id, Stamp(at, preloaded, len(arrivals)))
            if made is None:
                continue
            item, item_state = made if isinstance(made, tuple) else (made, None)
            arrivals.append((item, item_state))
        if not arrivals:
            return state
        add = with_items_first if self.newest_first else with_items
        state = add(state, self.items, [(item.id, item) for item, _ in arrivals])
        if self.states is None:
            return state
        fresh = self.fresh
        return add(
            state,
            self.states,
            [(item.id, s if s is not None or fresh is None else fresh()) for item, s in arrivals],
        )


# --- scenario events ---------------------------------------------------------------------------


def arrival(
    name: str,
    field: str,
    table: str | None,
    deliver: Deliver[S],
    *,
    help: str,
    description: str | None = None,
) -> tuple[str, EventType[S]]:
    """The event `name {field: id}`: one catalog item of `table` arriving now.

    `table` None: the id is not a row of one catalog table (e.g. a message inside a
    conversation), so authoring checks no reference."""

    def reduce(state: S, event: LoggedEvent) -> S:
        return deliver(state, [event.payload[field]], event.at, preloaded=False)

    reduce.__doc__ = help
    schema = id_payload(name, field, description)
    refs = {field: table} if table else {}
    return name, EventType(schema=schema, reduce=reduce, help=help, catalog_refs=refs)


def id_payload(name: str, field: str, description: str | None = None) -> type[Payload]:
    """The schema of the event `name {field: id}` naming one item (an arrival, a retraction)."""
    default = (
        f"catalog {field.removesuffix('_id').replace('_', ' ')} id"  # email_id → catalog email id
    )
    # Typed as create_model's **field_definitions: a literal dict would be matched against its
    # __config__, __base__… keywords too.
    fields: dict[str, Any] = {field: (str, Field(description=description or default))}
    return create_model(_schema_name(name), __base__=Payload, **fields)


Then = Callable[[S, Mapping[str, Any], float], S]  # (state, payload, at) → state


def preload(
    name: str,
    lists: Mapping[str, tuple[str, Deliver[S]]],
    *,
    help: str,
    environment: str,
    required: Iterable[str] = (),
    defaults: Mapping[str, list[str]] | None = None,
    descriptions: Mapping[str, str] | None = None,
    base: type[Payload] = Payload,
    then: Then[S] | None = None,
    refs: Mapping[str, str] | None = None,
) -> tuple[str, EventType[S]]:
    """The preload `name {<field>: [ids], …}`: for each `field → (table, deliver)`, in order,
    the ids (`["*"]` = every row of `table`) delivered as part of the starting world.

    Fields in `required` must be given; the others default to their `defaults` entry (e.g.
    `["*"]`: everything unless the scenario says otherwise), else to none. `descriptions` says
    what a list means where the table name alone does not. `base` adds the preload's other
    fields (numbers, ids already liked…), which `then(state, payload, at)` applies once
    everything is delivered. `refs` adds catalog references of `base`'s fields.
    """
    required = frozenset(required)
    defaults = dict(defaults or {})
    descriptions = dict(descriptions or {})

    def declared(field: str, table: str) -> tuple[Any, Any]:
        about = descriptions.get(field) or f'ids of the catalog\'s {table}; ["*"] = all of them'
        if field in required:
            return list[str], Field(description=about)
        default = defaults.get(field, [])
        return list[str], Field(default_factory=lambda: list(default), description=about)

    fields: dict[str, Any] = {f: declared(f, t) for f, (t, _) in lists.items()}
    schema = create_model(_schema_name(name), __base__=base, **fields)

    def reduce(state: S, event: LoggedEvent) -> S:
        catalog, payload, at = state.catalog, event.payload, event.at  # type: ignore[attr-defined]
        for field, (table, deliver) in lists.items():
            # The payload is logged as sent: a list left out takes its default here.
            given = payload.get(field)
            ids = catalog.expand(
                environment, table, defaults.get(field, []) if given is None else given
            )
            state = deliver(state, ids, at, preloaded=True)
        return then(state, payload, at) if then is not None else state

    reduce.__doc__ = help
    catalog_refs = {field: table for field, (table, _) in lists.items()} | dict(refs or {})
    event_type = EventType(
        schema=schema, reduce=reduce, help=help, catalog_refs=catalog_refs, preload=True
    )
    return name, event_type


def event_types(*declared: tuple[str, EventType[S]]) -> Mapping[str, EventType[S]]:
    """The environment's `event_types` mapping from `arrival(…)`, `preload(…)` and any
    hand-written `(name, EventType(…))`; a name declared twice is an error."""
    names = [name for name, _ in declared]
    twice = sorted({name for name in names if names.count(name) > 1})
    if twice:
        raise ValueError(f"event types declared twice: {', '.join(twice)}")
    return MappingProxyType(dict(declared))


def _schema_name(event: str) -> str:
    """`new_pull_request` → `NewPullRequest` (the name the API schema shows)."""
    return "".join(part.capitalize() for part in event.split("_"))
