"""What the two media sites (MicroFy's music, MicroTube's videos) share: counts that move between
events as `Waypoints` (plays, views, listeners, subscribers), the numbers their catalogs give,
the user's own numbered items, bounded texts, and pages of items that may not be there yet.

A moving count is shown rounded (to a whole number, or to the step of a compact "1.4M"), half
up, as `Waypoints.next_change(now, step=…)` assumes: so a page shows, re-renders and writes to
the evaluation tables the same number at the same simulated instant.

    plays = shown_count(showing(page, track.plays))         # on a page: re-rendered when it moves
    Table("videos", read_at(lambda tube: tube.videos.values()),
          {"id TEXT": "id", "views INTEGER": lambda v: shown_count(v.views.value_at(v.now))})
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import field
from typing import Any, Generic, TypeVar

from django.http import Http404
from pydantic import Field, create_model

from apps.kit.fields import ItemId
from apps.kit.state import EMPTY
from apps.kit.waypoints import Waypoints
from events.registry import ActionRejected
from events.schemas import Payload

S = TypeVar("S")
T = TypeVar("T")


# --- counts that move between events -------------------------------------------------------------


# How often a product refreshes a count on an open page when the count is nobody's trigger: a
# video's views, a song's plays, a paper's citations move on reload or every few minutes, not
# under the reader's eyes (simulated seconds). A trading page's prices tick live; a task's trigger
# that must reach an open page at once is an event (MicroHub's burst of stars), not a drift.
COUNT_REFRESH_S = 300.0


def shown_count(value: float, step: int = 1) -> int:
    """`value` as a page shows it: the nearest multiple of `step`, half up."""
    return math.floor(value / step + 0.5) * step


def showing(page: Any, series: Waypoints, step: int = 1, *, refresh: float | None = None) -> float:
    """The value of `series` at the page's `now`; the page (`apps.kit.pages.Page`) is rendered
    again when the value, rounded to `step`, next reads differently — or, with `refresh`
    (simulated seconds), an open page takes the new value up only at its next refresh, as a
    video feed's view counts do (a reload shows it at once)."""
    change = series.next_change(page.now, step=step)
    if refresh is None:
        page.changes_at(change)
    else:
        page.refreshes_at(change, refresh)
    return series.value_at(page.now)


class ReadAt(Generic[T]):
    """A row of an evaluation table read at `now`: the item's attributes, and the state and the
    moment, for the columns whose value moves with the clock."""

    __slots__ = ("item", "now", "state")

    def __init__(self, item: T, state: Any, now: float):
        self.item, self.state, self.now = item, state, now

    def __getattr__(self, name: str) -> Any:  # only called for what the row itself lacks
        return getattr(self.item, name)


def read_at(items: Callable[[S], Iterable[T]]) -> Callable[[S, float], Iterable[ReadAt[T]]]:
    """The `rows` of an `apps.kit.tables.Table` whose getters need `now` (or the state)."""
    return lambda state, now: (ReadAt(item, state, now) for item in items(state))


# --- catalog records, the user's items, texts --------------------------------------------------


def no_items() -> Any:
    """A state field that maps ids to items (read-only, in arrival order), empty at the start."""
    return field(default_factory=lambda: EMPTY)


def whole(value: Any, default: int = 0) -> int:
    """A catalog number (`"1200"`, `1200`, missing or garbled → `default`)."""
    try:
        return int(value)
    except (TypeError, ValueError):
        return default


def counting(collection: str, flag: str | None = None) -> Callable[[Any], int]:
    """How many items the state's `collection` (a mapping's values, or a tuple) holds, or only
    those whose attribute `flag` is true: a badge or a baseline, declared in one line."""

    def count(state: Any) -> int:
        items = getattr(state, collection)
        if flag is None:
            return len(items)
        values = items.values() if isinstance(items, Mapping) else items
        return sum(1 for item in values if getattr(item, flag))

    count.__doc__ = f"How many {collection}" + (f" are {flag}." if flag else ".")
    return count


def numbered_id(existing: Mapping[str, Any], prefix: str) -> str:
    """`<prefix>-<n>` for the next item the user creates (the original's id shape: the count
    plus one, or the next free number). Decided once and logged, so replay reuses it."""
    n = len(existing) + 1
    while f"{prefix}-{n}" in existing:
        n += 1
    return f"{prefix}-{n}"


def bounded_text(
    payload: Mapping[str, Any], key: str, most: int, *, too_long: str, empty: str | None = None
) -> str:
    """`payload[key]` without surrounding blanks; a 400 `"<key>: <empty>"` when nothing is left
    (unless `empty` is None: then blank is allowed), `"<key>: <too_long>"` past `most` characters."""
    text = str(payload.get(key) or "").strip()
    if empty is not None and not text:
        raise ActionRejected(f"{key}: {empty}")
    if len(text) > most:
        raise ActionRejected(f"{key}: {too_long}")
    return text


def id_payload(name: str, field: str, description: str) -> type[Payload]:
    """The payload of an action on one item: `{<field>: id}` (e.g. `TrackId {track_id}`)."""
    fields: dict[str, Any] = {field: (ItemId, Field(description=description))}
    return create_model(name, __base__=Payload, **fields)


def present(item: T | None, what: str) -> T:
    """`item`, or the site's 404 page "no such <what>": unknown and not arrived yet look alike."""
    if item is None:
        raise Http404(f"no such {what}")
    return item
