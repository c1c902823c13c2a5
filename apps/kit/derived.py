"""Memoising what environments derive from a folded state: screens, counts, badges.

A state is immutable and the fold hands out the same object until an event changes it (page
views change nothing), so a pure function of (state, hashable args) can be computed once per
state instead of on every request for it. Keyed by the state's identity — hashing a whole
mailbox would cost what the cache saves. An entry refers to its state weakly and goes when the
state does, so no other object can take over its id while it lives, and the entries of a
closed run (whose fold and screens are forgotten) do not keep its states alive until 256 newer
ones push them out: memory comes back as runs end.
"""

from __future__ import annotations

import functools
import weakref
from collections.abc import Callable
from typing import Concatenate, ParamSpec, TypeVar

from events.lru import LRU

S = TypeVar("S")
P = ParamSpec("P")
R = TypeVar("R")


def per_state(
    maxsize: int = 256,
) -> Callable[[Callable[Concatenate[S, P], R]], Callable[Concatenate[S, P], R]]:
    """Decorator: memoise `fn(state, *args, **kwargs)`; every argument after the state hashable."""

    def decorate(fn: Callable[Concatenate[S, P], R]) -> Callable[Concatenate[S, P], R]:
        entries: LRU[tuple, tuple[Callable[[], S | None], R]] = LRU(maxsize)

        @functools.wraps(fn)
        def memoised(state: S, *args: P.args, **kwargs: P.kwargs) -> R:
            key = (id(state), args, tuple(sorted(kwargs.items())))
            entry = entries.get(key)
            if entry is not None and entry[0]() is state:
                return entry[1]
            result = fn(state, *args, **kwargs)  # two threads may both compute: same result
            entries.put(key, (held(state, lambda _: entries.pop(key)), result))
            return result

        return memoised

    return decorate


def held(state: S, gone: Callable[[object], object]) -> Callable[[], S | None]:
    """A reference to `state` that calls `gone` once the state is collected — or, for a value
    that cannot be referred to weakly (a tuple), a strong one."""
    try:
        return weakref.ref(state, gone)
    except TypeError:
        return lambda: state
