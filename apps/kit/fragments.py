"""Rendering a repeated piece of a page (a message row, a track, a post) once per distinct input.

Rows are most of a long list's rendering, and the same row is shown over and over: on every
screen it belongs to, on every reload and every live push. `render_fragment(template, **inputs)`
renders `template` with exactly `inputs` as its context — nothing else of the page leaks in — so
the inputs are the whole key: a cached fragment is always what a fresh render would give. Inputs
must be hashable (frozen dataclasses, strings, numbers). Pass what changes with the clock as its
text ("5 min ago"), not as `now`, so a live clock keeps hitting the cache.
"""

from __future__ import annotations

import functools

from django.conf import settings
from django.template.loader import get_template
from django.utils.safestring import SafeString

FRAGMENTS_KEPT = 4096  # about ten full mailboxes of the largest catalog


def render_fragment(template: str, **inputs) -> SafeString:
    """`template` rendered with `inputs` as its whole context (each input hashable). Callers
    pass inputs in the same order each time: the order is part of the key."""
    if settings.DEBUG:  # an edited template shows at once
        return _render(template, tuple(inputs.items()))
    return _cached(template, tuple(inputs.items()))


def _render(template: str, inputs: tuple) -> SafeString:
    return SafeString(get_template(template).render(dict(inputs)))


# functools' C implementation: thread-safe, and on the hot path (a row per message) several
# times cheaper than a Python LRU.
_cached = functools.lru_cache(maxsize=FRAGMENTS_KEPT)(_render)


def cache_info() -> tuple[int, int]:
    """(hits, misses) since the process started or the last `clear`."""
    info = _cached.cache_info()
    return info.hits, info.misses


def clear() -> None:
    _cached.cache_clear()
