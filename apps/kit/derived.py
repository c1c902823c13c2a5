"""Memoising what environments derive from a folded state: screens, counts, badges.

A state is immutable and the fold hands out the same object until an event changes it (page
views change nothing), so a pure function of (state, hashable args) can be computed once per
state instead of on every request for it. Keyed by the state's identity — hashing a whole
mailbox would cost what the cache saves — and holding the state itself, so that while an
entry lives no other object can take over its id.
"""

from __future__ import annotations

import functools
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
        entries: LRU[tuple, tuple[S, R]] = LRU(maxsize)

        @functools.wraps(fn)
        def memoised(state: S, *args: P.args, **kwargs: P.kwargs) -> R:
            key = (id(state), args, tuple(sorted(kwargs.items())))
            entry = entries.get(key)
            if entry is not None and entry[0] is state:
                return entry[1]
            result = fn(state, *args, **kwargs)  # two threads may both compute: same result
            entries.put(key, (state, result))
            return result

        return memoised

    return decorate
