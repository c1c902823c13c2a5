"""A bounded, thread-safe least-recently-used map: the in-process caches of the request path."""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable
from typing import Generic, TypeVar

K = TypeVar("K", bound=Hashable)
V = TypeVar("V")


class LRU(Generic[K, V]):
    """At most `size` entries — and, given `weigh`, at most `budget` of their summed weights
    (bytes, say: a few large values must not hold what many small ones would)."""

    def __init__(
        self, size: int, *, budget: int | None = None, weigh: Callable[[V], int] | None = None
    ):
        if (budget is None) != (weigh is None):
            raise ValueError("an LRU's budget and its weigh function go together")
        self.size = size
        self.budget = budget
        self._weigh = weigh
        self._held = 0
        self._entries: OrderedDict[K, V] = OrderedDict()
        # Request threads, the ticker and consumers share these. Reentrant: dropping an entry
        # can free the last reference to a state whose weakly held entry then leaves too
        # (apps.kit.derived), on the same thread, under the same lock.
        self._lock = threading.RLock()

    def get(self, key: K) -> V | None:
        with self._lock:
            value = self._entries.get(key)
            if value is not None:
                self._entries.move_to_end(key)
            return value

    def put(self, key: K, value: V, *, unless: Callable[[V], bool] | None = None) -> None:
        """Store `value`, dropping the least recently used entry beyond `size` — unless the
        entry already there makes `unless` true (decided under the lock, so no race can undo it)."""
        with self._lock:
            current = self._entries.get(key)
            if current is not None and unless is not None and unless(current):
                return
            if current is not None:
                self._release(self._entries.pop(key))
            weight = self._weigh(value) if self._weigh is not None else 0
            if self.budget is not None and weight > self.budget:
                return  # alone over the budget: keeping it would push out everything else
            self._entries[key] = value
            self._held += weight
            while len(self._entries) > self.size or (
                self.budget is not None and self._held > self.budget
            ):
                self._release(self._entries.popitem(last=False)[1])

    def pop(self, key: K) -> V | None:
        with self._lock:
            value = self._entries.pop(key, None)
            if value is not None:
                self._release(value)
            return value

    def discard_where(self, drop: Callable[[K], bool]) -> None:
        """Forget every entry whose key `drop` selects (a closed run's)."""
        with self._lock:
            for key in [key for key in self._entries if drop(key)]:
                self._release(self._entries.pop(key))

    def clear(self) -> None:
        with self._lock:
            self._entries.clear()
            self._held = 0

    def _release(self, value: V) -> None:
        if self._weigh is not None:
            self._held -= self._weigh(value)
