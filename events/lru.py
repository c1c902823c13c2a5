"""A bounded, thread-safe least-recently-used map: the in-process caches of the request path."""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable
from typing import Generic, TypeVar

K = TypeVar("K", bound=Hashable)
V = TypeVar("V")


class LRU(Generic[K, V]):
    def __init__(self, size: int):
        self.size = size
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
            self._entries[key] = value
            self._entries.move_to_end(key)
            while len(self._entries) > self.size:
                self._entries.popitem(last=False)

    def pop(self, key: K) -> V | None:
        with self._lock:
            return self._entries.pop(key, None)

    def discard_where(self, drop: Callable[[K], bool]) -> None:
        """Forget every entry whose key `drop` selects (a closed run's)."""
        with self._lock:
            for key in [key for key in self._entries if drop(key)]:
                del self._entries[key]

    def clear(self) -> None:
        with self._lock:
            self._entries.clear()
