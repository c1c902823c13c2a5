"""State as of any log position: `state_at(run, seq)` folds catalog + events.

The cache keeps, per run, the last state folded and its seq, and fast-forwards from there by
applying only the newer events. States are immutable, so a cached state can be handed out
without copying. The cache is an optimisation behind `state_at`, never a second source of truth:
a fold from scratch gives the same state (tested).
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from typing import Any

from apps.catalog.loader import load_catalog
from events.models import Event, Run
from events.registry import LoggedEvent, get_environment

CACHE_SIZE = 512

_FIELDS = ("seq", "at", "kind", "type", "payload")


def logged_events(run_id: int, after: int = 0, upto: int | None = None) -> list[LoggedEvent]:
    rows = Event.objects.filter(run_id=run_id, seq__gt=after)
    if upto is not None:
        rows = rows.filter(seq__lte=upto)
    return [LoggedEvent(*row) for row in rows.order_by("seq").values_list(*_FIELDS)]


def initial_state(run: Run) -> Any:
    environment = get_environment(run.environment)
    return environment.initial_state(load_catalog(run.catalog_dir))


def fold_from_scratch(run: Run, seq: int | None = None) -> tuple[Any, int]:
    environment = get_environment(run.environment)
    events = logged_events(run.pk, 0, seq)
    state = environment.fold(initial_state(run), events)
    return state, (events[-1].seq if events else 0)


class _Cache:
    def __init__(self, size: int):
        self.size = size
        self.entries: OrderedDict[tuple[int, str], tuple[int, Any]] = OrderedDict()
        self.lock = threading.Lock()

    def get(self, key):
        with self.lock:
            entry = self.entries.get(key)
            if entry is not None:
                self.entries.move_to_end(key)
            return entry

    def put(self, key, seq: int, state: Any) -> None:
        with self.lock:
            current = self.entries.get(key)
            if current is not None and current[0] > seq:
                return  # a concurrent caller already folded further
            self.entries[key] = (seq, state)
            self.entries.move_to_end(key)
            while len(self.entries) > self.size:
                self.entries.popitem(last=False)

    def clear(self) -> None:
        with self.lock:
            self.entries.clear()


_cache = _Cache(CACHE_SIZE)


def clear_cache() -> None:
    _cache.clear()


def state_at(run: Run, seq: int | None = None) -> Any:
    """The environment state of `run` as of log position `seq` (default: the whole log)."""
    environment = get_environment(run.environment)
    key = (run.pk, run.catalog_hash)
    cached = _cache.get(key)
    if cached is not None and (seq is None or cached[0] <= seq):
        last_seq, state = cached
        newer = logged_events(run.pk, last_seq, seq)
        if not newer:
            return state
        state = environment.fold(state, newer)
        last_seq = newer[-1].seq
    else:
        state, last_seq = fold_from_scratch(run, seq)
    if seq is None or cached is None or last_seq >= cached[0]:
        _cache.put(key, last_seq, state)
    return state
