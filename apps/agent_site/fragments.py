"""Rendering a repeated piece of a page (a message row, a track, a post) once per distinct input.

Rows are most of a long list's rendering, and the same row is shown over and over: on every
screen it belongs to, on every reload and every live push. `render_fragment(template, **inputs)`
renders `template` with exactly `inputs` as its context — nothing else of the page leaks in — so
the inputs are the whole key: a cached fragment is always what a fresh render would give. Inputs
must be hashable (frozen dataclasses, strings, numbers). Pass what changes with the clock as its
text ("5 min ago"), not as `now`, so a live clock keeps hitting the cache.
"""

from __future__ import annotations

from django.conf import settings
from django.template.loader import get_template
from django.utils.safestring import SafeString

from events.lru import LRU

FRAGMENTS_KEPT = 4096  # about ten full mailboxes of the largest catalog

_rendered: LRU[tuple, SafeString] = LRU(FRAGMENTS_KEPT)
_counts = {"hits": 0, "misses": 0}  # approximate under threads: for tests and tuning only


def render_fragment(template: str, **inputs) -> SafeString:
    key = (template, tuple(sorted(inputs.items())))
    if not settings.DEBUG:  # with DEBUG, an edited template shows at once
        cached = _rendered.get(key)
        if cached is not None:
            _counts["hits"] += 1
            return cached
    _counts["misses"] += 1
    html = SafeString(get_template(template).render(inputs))
    _rendered.put(key, html)
    return html


def cache_info() -> tuple[int, int]:
    """(hits, misses) since the process started."""
    return _counts["hits"], _counts["misses"]


def clear() -> None:
    _rendered.clear()
