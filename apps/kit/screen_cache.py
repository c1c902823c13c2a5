"""Rendered screens kept while nothing they show can have changed.

A monitoring agent mostly reloads the same page while it waits, and the run's state rarely moves
between two loads. A screen is a pure function of the run's folded state, the simulated clock
(every clock-dependent display registers when it next changes: `Page.changes_at`), the URL and
the htmx headers — the contract every environment view already keeps for live pages. So the HTML
rendered for one load serves the next as long as the state is the same object, the clock has not
reached the page's next change, and the request asks for the same URL the same way.

Only one thing in a page is per request: the CSRF token. Screens are rendered with a placeholder
in its place and every response gets its own request's token, so a cached page's forms work for
whoever loads it. Pages that show one-shot messages (the toast after an action), POSTs, error
statuses, live re-renders and time travel are never cached.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from django.conf import settings
from django.contrib.messages import get_messages
from django.http import HttpRequest, HttpResponse

from apps.kit.csrf import csrf_token

CSRF_PLACEHOLDER = "__sentinel_csrf_token__"
# Request headers a view may read to decide what to render (django-htmx's request.htmx).
_HTMX_HEADERS = ("HTTP_HX_REQUEST", "HTTP_HX_BOOSTED", "HTTP_HX_TARGET", "HTTP_HX_TRIGGER")
MAX_SCREENS = 512  # oldest dropped first…
MAX_SCREEN_BYTES = 24 * 1024 * 1024  # …and beyond this much HTML (512 of the largest: 50 MB)


@dataclass(frozen=True)
class Screen:
    state: Any  # held, so its identity cannot be reused while the entry lives
    live_seq: int
    rendered_at: float  # simulated second the screen was rendered at
    valid_until: float  # when a reload next reads differently (inf: nothing shown moves)
    html: str  # with CSRF_PLACEHOLDER for the token
    live_due: float | None = None  # the page's next live push (its `next_change`)


_screens: OrderedDict[tuple, Screen] = OrderedDict()
_held = [0]  # characters of HTML the kept screens hold (≈ bytes: the pages are ASCII markup)
_lock = threading.Lock()
_counts = {"hits": 0, "misses": 0}


def enabled() -> bool:
    return getattr(settings, "SENTINEL_SCREEN_CACHE", True)


def _key(request: HttpRequest, page) -> tuple:
    headers = tuple(request.META.get(name, "") for name in _HTMX_HEADERS)
    return (page.run.pk, request.get_full_path(), headers)


def _cacheable(request: HttpRequest, page) -> bool:
    return (
        enabled()
        and request.method in ("GET", "HEAD")
        and not page.live
        and not page.read_only
        and not len(get_messages(request))  # a toast is shown once (len() does not consume it)
    )


def _with_token(request: HttpRequest, html: str, status: int) -> HttpResponse:
    return HttpResponse(html.replace(CSRF_PLACEHOLDER, csrf_token(request)), status=status)


def cached_render(
    request: HttpRequest, page, render: Callable[[dict[str, Any]], str], status: int = 200
) -> HttpResponse:
    """The screen for this request: the one kept from an earlier identical load if nothing it
    shows can have changed since, else `render(extra_context)` (and kept when it may be)."""
    if not _cacheable(request, page):
        return _with_token(request, render({"csrf_token": CSRF_PLACEHOLDER}), status)
    key = _key(request, page)
    with _lock:
        screen = _screens.get(key)
        if screen is not None:
            _screens.move_to_end(key)
    if (
        screen is not None
        and screen.state is page.state
        and screen.live_seq == page.live_seq
        and screen.rendered_at <= page.now < screen.valid_until
    ):
        # What the render noted: when a reload reads differently, when the open page is pushed.
        page.note_changes(
            screen.valid_until if screen.valid_until != float("inf") else None, screen.live_due
        )
        _counts["hits"] += 1
        return _with_token(request, screen.html, status)
    _counts["misses"] += 1
    html = render({"csrf_token": CSRF_PLACEHOLDER})
    if status == 200:
        until = page.reads_same_until
        valid_until = until if until is not None else float("inf")
        with _lock:
            _drop(key)
            _screens[key] = Screen(
                page.state, page.live_seq, page.now, valid_until, html, page.next_change
            )
            _held[0] += len(html)
            while len(_screens) > MAX_SCREENS or _held[0] > MAX_SCREEN_BYTES:
                _drop(next(iter(_screens)))
    return _with_token(request, html, status)


def _drop(key: tuple) -> None:
    """Forget one screen (under the lock)."""
    screen = _screens.pop(key, None)
    if screen is not None:
        _held[0] -= len(screen.html)


def on_run_closed(sender: object, *, run_id: int, **_: object) -> None:
    """Drop a closed run's screens (each holds its HTML and the state it was rendered from):
    connected to the engine's `run_closed` notice in KitConfig.ready()."""
    with _lock:
        for key in [key for key in _screens if key[0] == run_id]:
            _drop(key)


def cache_info() -> tuple[int, int]:
    """(hits, misses) of cacheable loads since the last `clear()`."""
    return _counts["hits"], _counts["misses"]


def clear() -> None:
    """Forget every kept screen and the counts (tests; memory is otherwise bounded by the LRU)."""
    with _lock:
        _screens.clear()
        _held[0] = 0
        _counts.update(hits=0, misses=0)
