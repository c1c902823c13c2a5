"""Live push: when a run's log grows, open pages of that run get their live regions re-rendered.

The flow, one path for every backend:

1. Whoever appends `scenario` or `action` events (the ticker in any backend, a lazy catch-up
   inside a request, an agent action) calls `log_grew(run_id, seq)`. After the transaction
   commits, a `run.log_grew` message goes to the channel group `run.<id>` through the
   configured channel layer (in-memory embedded, Redis in production).
2. Each subscribed socket (`events.consumers.RunLiveConsumer`) knows which URL its page shows.
   It asks `live_regions(...)` for that URL: the page's normal view is rendered in-process, for
   the same run and query, as an HTMX partial request flagged `sentinel_live` — so it logs no
   view event and performs no implicit action — and the elements marked `data-live` are cut out.
3. The regions go to the browser as out-of-band swaps (`hx-swap-oob="true"`); the client
   (static/site/live.js) swaps them in place.

One render per (run, URL, log position) is shared by every subscriber in the process, down to
the encoded frame: CSRF token values of forms in pushed regions are left blank and each browser
fills in its own page's token, so a form in a pushed region still posts.
"""

from __future__ import annotations

import asyncio
import json
import logging
import re
import threading
import weakref
from collections import OrderedDict
from dataclasses import dataclass
from functools import cached_property
from urllib.parse import urlsplit

from asgiref.sync import async_to_sync
from django.db import close_old_connections, transaction
from django.db.models import Max
from django.http import Http404, HttpRequest, QueryDict
from django.middleware.csrf import CSRF_ALLOWED_CHARS
from django.urls import Resolver404, resolve, reverse
from django.utils.crypto import get_random_string

from events.models import Event, EventKind, Run

log = logging.getLogger(__name__)

LIVE_KINDS = (EventKind.SCENARIO, EventKind.ACTION)
MESSAGE_TYPE = "run.log_grew"
POLL_INTERVAL_MS = 2000  # the fallback when the socket cannot connect (documented in the shell)


def group_name(run_id: int) -> str:
    return f"run.{run_id}"


# ---------------------------------------------------------------------------------------------
# Broadcast (sync callers: the scheduler, commands; any thread, any backend)


def log_grew(run_id: int, seq: int) -> None:
    """Tell subscribers of the run that its log grew to `seq`, once the write is committed.

    Never raises: a push is a convenience (pages also poll and reload), an append is not.
    """
    transaction.on_commit(lambda: _send(run_id, seq))


def _send(run_id: int, seq: int) -> None:
    from channels.layers import get_channel_layer

    layer = get_channel_layer()
    if layer is None:
        return
    message = {"type": MESSAGE_TYPE, "run": run_id, "seq": seq}
    try:
        loop = asyncio.get_running_loop()
    except RuntimeError:
        loop = None
    try:
        if loop is not None:  # called on an event loop's own thread: async_to_sync would refuse
            loop.create_task(layer.group_send(group_name(run_id), message))
        else:
            async_to_sync(layer.group_send)(group_name(run_id), message)
    except Exception:  # noqa: BLE001 — e.g. Redis unreachable: the page falls back to polling
        log.warning("live push for run %s failed", run_id, exc_info=True)


def last_live_seq(run_id: int) -> int:
    """Log position of the run's last scenario or action event (0 when none)."""
    found = Event.objects.filter(run_id=run_id, kind__in=LIVE_KINDS).aggregate(m=Max("seq"))["m"]
    return found or 0


# ---------------------------------------------------------------------------------------------
# Rendering a page's live regions


class NotLive(Exception):
    """The URL cannot be re-rendered for this run (another run, unknown page, view error)."""


def page_path_for(run: Run, url: str) -> tuple[str, str]:
    """Split and check a page URL sent by a client: it must be one of *this* run's pages."""
    parts = urlsplit(url or "")
    run_home = reverse("run-home", kwargs={"token": run.token})
    if parts.scheme or parts.netloc or not parts.path.startswith(run_home):
        raise NotLive("the URL is not a page of this run")
    return parts.path, parts.query


_PLACEHOLDER_SECRET = get_random_string(32, allowed_chars=CSRF_ALLOWED_CHARS)
_CSRF_INPUT = re.compile(r'(name="csrfmiddlewaretoken" value=")[^"]*(")')


def without_csrf_tokens(html: str) -> str:
    """Blank the CSRF tokens of forms in pushed HTML: one push serves every subscriber, and
    each browser fills in its own page's token (static/site/live.js)."""
    return _CSRF_INPUT.sub(r"\1\2", html)


def live_request(path: str, query: str, host: str = "testserver") -> HttpRequest:
    """A GET for `path?query` as an HTMX partial request, flagged so @run_page does not log it."""
    from django_htmx.middleware import HtmxDetails

    request = HttpRequest()
    request.method = "GET"
    request.path = request.path_info = path
    request.GET = QueryDict(query)
    name, _, port = host.partition(":")
    request.META = {
        "REQUEST_METHOD": "GET",
        "PATH_INFO": path,
        "QUERY_STRING": query,
        "SERVER_NAME": name or "testserver",
        "SERVER_PORT": port or "80",
        "HTTP_HOST": host or "testserver",
        "HTTP_HX_REQUEST": "true",
        "CSRF_COOKIE": _PLACEHOLDER_SECRET,
    }
    request.htmx = HtmxDetails(request)
    request.sentinel_live = True
    return request


def render_page(run: Run, url: str, host: str = "testserver") -> str:
    """The page at `url` of `run`, rendered by its own view as a live (side-effect-free) request."""
    path, query = page_path_for(run, url)
    try:
        match = resolve(path)
    except Resolver404:
        raise NotLive("no page at this URL") from None
    if match.kwargs.get("token") != run.token:
        raise NotLive("the URL is not a page of this run")
    try:
        response = match.func(live_request(path, query, host), *match.args, **match.kwargs)
    except Http404 as exc:  # the run closed, or the open item was purged meanwhile
        raise NotLive(f"the page is gone: {exc}") from None
    if hasattr(response, "render"):
        response.render()
    if response.status_code != 200:
        raise NotLive(f"the page answered {response.status_code}")
    return response.content.decode(response.charset or "utf-8")


_ATTRS = r"""(?:\s+[^\s"'>/=]+(?:\s*=\s*(?:"[^"]*"|'[^']*'|[^\s"'>]+))?)*"""
_START_TAG = re.compile(r"<([a-zA-Z][\w-]*)(" + _ATTRS + r")\s*/?>")
_LIVE_ATTR = re.compile(r"\sdata-live(?=[\s=/>]|$)")
_ID_ATTR = re.compile(r"""\sid\s*=\s*(?:"([^"]*)"|'([^']*)'|([^\s"'>]+))""")
_BETWEEN_TAGS = re.compile(r">\s+<")


def _end_of(html: str, tag: str, start: int) -> int:
    """Offset just past the end tag closing the `tag` element whose start tag ends at `start`."""
    depth = 1
    for match in re.finditer(rf"<(/?){tag}(?=[\s/>])[^>]*>", html[start:], re.IGNORECASE):
        depth += -1 if match.group(1) else 1
        if depth == 0:
            return start + match.end()
    raise ValueError(f"<{tag}> live region is not closed")


def extract_regions(html: str) -> list[tuple[str, str]]:
    """The `data-live` regions of a rendered page: [(id, outer HTML)], outermost, in order.

    A scan for the marker rather than a full HTML parse (a push renders on the hot path); it
    needs each region to be one element with an explicit end tag, which templates give.
    Whitespace-only runs between tags are collapsed (rendering is the same; the push smaller).
    """
    regions, position = [], 0
    while (marker := html.find("data-live", position)) >= 0:
        tag_start = html.rfind("<", 0, marker)
        match = _START_TAG.match(html, tag_start)
        position = marker + len("data-live")
        if match is None or match.end() <= marker or not _LIVE_ATTR.search(match.group(2)):
            continue  # the words "data-live" in text or another attribute's value
        found = _ID_ATTR.search(match.group(2))
        if found is None:
            continue
        region_id = next(group for group in found.groups() if group is not None)
        end = _end_of(html, match.group(1), match.end())
        outer = html[tag_start:end]
        if "<pre" not in outer and "<textarea" not in outer:
            outer = _BETWEEN_TAGS.sub("> <", outer)
        regions.append((region_id, outer))
        position = end
    return regions


def as_oob(regions: list[tuple[str, str]]) -> str:
    """Regions as out-of-band swaps: each root element gets hx-swap-oob="true"."""
    return "\n".join(
        re.sub(r"^<([a-zA-Z][\w-]*)", r'<\1 hx-swap-oob="true"', outer, count=1)
        for _, outer in regions
    )


@dataclass(frozen=True)
class LiveUpdate:
    url: str  # the page URL rendered (the client ignores updates for a page it has left)
    seq: int  # the log position the render includes at least
    html: str  # out-of-band swaps, CSRF token values blank (the client fills in its own)

    def message(self) -> dict:
        return {"type": "regions", "url": self.url, "seq": self.seq, "html": self.html}

    @cached_property
    def text(self) -> str:
        """The message as one JSON frame, encoded once for all subscribers."""
        return json.dumps(self.message())


def render_update(run: Run, url: str, host: str = "testserver") -> LiveUpdate:
    """Render `url` now and cut out its live regions (sync: call from a worker thread)."""
    seq = last_live_seq(run.pk)
    html = as_oob(extract_regions(render_page(run, url, host)))
    return LiveUpdate(url=url, seq=seq, html=without_csrf_tokens(html))


class _SharedRenders:
    """One render per (run, URL, log position) for all subscribers on one event loop."""

    SIZE = 256

    def __init__(self) -> None:
        self.updates: OrderedDict[tuple[int, str], LiveUpdate] = OrderedDict()
        self.locks: dict[tuple[int, str], asyncio.Lock] = {}

    async def get(self, run: Run, url: str, seq: int, host: str) -> LiveUpdate:
        from channels.db import database_sync_to_async

        key = (run.pk, url)
        lock = self.locks.setdefault(key, asyncio.Lock())
        async with lock:
            cached = self.updates.get(key)
            if cached is not None and cached.seq >= seq:
                self.updates.move_to_end(key)
                return cached
            update = await database_sync_to_async(render_update)(run, url, host)
            self.updates[key] = update
            self.updates.move_to_end(key)
            while len(self.updates) > self.SIZE:
                old, _ = self.updates.popitem(last=False)
                self.locks.pop(old, None)
            return update


_renders: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
_renders_guard = threading.Lock()


async def shared_update(run: Run, url: str, seq: int, host: str = "testserver") -> LiveUpdate:
    """The live regions of `url` including at least log position `seq`, rendered once per loop."""
    loop = asyncio.get_running_loop()
    with _renders_guard:
        renders = _renders.get(loop)
        if renders is None:
            renders = _renders[loop] = _SharedRenders()
    return await renders.get(run, url, seq, host)


def open_run(token: str) -> Run | None:
    close_old_connections()
    return Run.objects.open_by_token(token)
