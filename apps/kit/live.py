"""Live push: open pages of a run get their live regions re-rendered when the run's log grows
and when what they show changes with the clock.

The flow, one path for every backend:

1. Whoever appends `scenario` or `action` events (the ticker in any backend, a lazy catch-up
   inside a request, an agent action) calls the engine's `events.notifications.log_grew(run_id,
   seq)`; whoever moves a clock by hand (`/advance`, starting the clock, a fast-forward skip)
   calls `clock_moved`.
   After the transaction commits, this module hears it and sends a `run.log_grew` /
   `run.clock_moved` message to the channel group `run.<id>` through the configured channel
   layer (in-memory embedded, Redis in production).
2. Each subscribed socket (`apps.kit.consumers.RunLiveConsumer`) knows which URL its page shows.
   It asks `shared_update(...)` for that URL: the page's normal view renders it in-process, for
   the same run and query, flagged `sentinel_live` — so it logs no view event and performs no
   implicit action. The page's templates mark their live regions with a tag
   (apps/kit/templatetags/live.py) which, on such a request, records each region's HTML
   on the request (`request.sentinel_live_regions`): nothing is cut out of the HTML afterwards.
   The render also says when what it shows next changes with the clock
   (`request.sentinel_page.next_change`, simulated seconds); the socket sets a timer for it.
3. The regions go to the browser as out-of-band swaps (`hx-swap-oob="true"`); the client
   (static/site/live.js) swaps them in place.

One render per (run, URL, log position, clock window) is shared by every subscriber and every
poll in the process, down to the encoded frame: CSRF token values of forms in pushed regions are
left blank and each browser fills in its own page's token, so a form in a pushed region still
posts. A clock window ends at the render's `next_change`: until then, a render at a later
simulated time would show the same thing.
"""

from __future__ import annotations

import asyncio
import copy
import json
import logging
import re
import threading
from dataclasses import dataclass
from functools import cached_property
from urllib.parse import urlsplit

from asgiref.sync import async_to_sync
from django.db import close_old_connections
from django.db.models import Max
from django.http import Http404, HttpRequest, QueryDict
from django.middleware.csrf import CSRF_ALLOWED_CHARS
from django.urls import Resolver404, resolve, reverse
from django.utils.crypto import get_random_string

from apps.kit import request_attrs
from apps.kit.visible import visible_signature
from events.clock import CLOCK_FIELDS
from events.lru import LRU
from events.models import Event, Run
from events.notifications import (
    LIVE_KINDS,
    clock_moved_signal,
    log_grew_signal,
    run_closed_signal,
)

log = logging.getLogger(__name__)

LOG_GREW = "run.log_grew"
CLOCK_MOVED = "run.clock_moved"
POLL_INTERVAL_MS = 2000  # the fallback when the socket cannot connect (documented in the shell)


def group_name(run_id: int) -> str:
    return f"run.{run_id}"


# ---------------------------------------------------------------------------------------------
# Broadcast: the engine's notices (events.notifications, sent after commit) become channel
# messages to the run's group. Connected in KitConfig.ready().


def on_log_grew(sender: object, *, run_id: int, seq: int, **_: object) -> None:
    """Tell subscribers of the run that its log grew to `seq`."""
    _send(run_id, {"type": LOG_GREW, "run": run_id, "seq": seq})


def on_clock_moved(sender: object, *, run_id: int, **_: object) -> None:
    """Tell subscribers of the run that its clock was moved or started: each re-checks when its
    page next changes. The message carries the clock as committed, read once here for all."""
    reading = clock_reading(run_id)
    if reading is not None:
        _send(run_id, {"type": CLOCK_MOVED, "run": run_id, "clock": reading})


def on_run_closed(sender: object, *, run_id: int, **_: object) -> None:
    """Forget the renders of a closed run: its pages are never pushed again."""
    _renders.discard_where(lambda key: key[0] == run_id)


def connect() -> None:
    log_grew_signal.connect(on_log_grew, dispatch_uid="kit.live.log_grew")
    clock_moved_signal.connect(on_clock_moved, dispatch_uid="kit.live.clock_moved")
    run_closed_signal.connect(on_run_closed, dispatch_uid="kit.live.run_closed")


def _send(run_id: int, message: dict) -> None:
    from channels.layers import get_channel_layer

    layer = get_channel_layer()
    if layer is None or nobody_listens(layer, group_name(run_id)):
        return
    try:
        loop = asyncio.get_running_loop()
    except RuntimeError:
        loop = None
    try:
        if loop is not None:  # called on an event loop's own thread: async_to_sync would refuse
            loop.create_task(layer.group_send(group_name(run_id), message))
        else:
            async_to_sync(layer.group_send)(group_name(run_id), message)
    except Exception:  # e.g. Redis unreachable: the page falls back to polling
        log.warning("live push for run %s failed", run_id, exc_info=True)


def nobody_listens(layer: object, group: str) -> bool:
    """True when the in-process layer (embedded) has no socket in `group`: most runs have no
    open page, and handing each notice to the event loop cost a thread hop per fire (≈1 ms of a
    reset). A shared layer (Redis) reaches other processes' sockets: always sent."""
    from channels.layers import InMemoryChannelLayer

    return isinstance(layer, InMemoryChannelLayer) and not layer.groups.get(group)


def last_live_seq(run_id: int) -> int:
    """Log position of the run's last scenario or action event (0 when none)."""
    found = Event.objects.filter(run_id=run_id, kind__in=LIVE_KINDS).aggregate(m=Max("seq"))["m"]
    return found or 0


# ---------------------------------------------------------------------------------------------
# The run's clock as a socket last read it (fields that change while a run lives)


def clock_reading(run_id: int) -> dict | None:
    """The run's clock fields, fresh from the database, as a channel-layer-safe dict (None: the
    run is gone). Speed and clock mode never change; a closed run's pages stop rendering."""
    return Run.objects.filter(pk=run_id).values(*CLOCK_FIELDS).first()


def with_clock(run: Run, reading: dict) -> Run:
    """A copy of `run` whose clock reads `reading` (events.clock's functions take a Run)."""
    clock = copy.copy(run)
    for name in CLOCK_FIELDS:
        setattr(clock, name, reading[name])
    return clock


def subscription(run_id: int) -> tuple[int, dict | None]:
    """What a socket reads when a page subscribes: the log position and the clock."""
    return last_live_seq(run_id), clock_reading(run_id)


# ---------------------------------------------------------------------------------------------
# Rendering a page's live regions


class NotLive(Exception):
    """The URL cannot be re-rendered for this run (another run, unknown page, view error)."""


MAX_URL_CHARS = 2048
LIVE_PAGE = "sentinel_live_page"  # attribute marking a view a live request may render


def renderable(view):
    """Mark `view` as a page a live request may render (apps.kit.pages.run_page does):
    a view that reads the run and acts only through `Page.act`, which refuses on a live render.
    Nothing else under a run's URL is ever called by the live protocol — not the task URL
    (it starts the clock), the contact page (it records a contact) or the JSON actions."""
    setattr(view, LIVE_PAGE, True)
    return view


def page_path_for(run: Run, url: object) -> tuple[str, str]:
    """Split and check a page URL sent by a client: it must be one of *this* run's pages."""
    if not isinstance(url, str) or not url:
        raise NotLive("the URL must be a non-empty string")
    if len(url) > MAX_URL_CHARS or "\x00" in url:
        raise NotLive(f"the URL must be at most {MAX_URL_CHARS} characters, without NUL")
    try:
        parts = urlsplit(url)
    except ValueError as exc:  # e.g. "http://[::1": an unclosed IPv6 host
        raise NotLive(f"the URL cannot be read: {exc}") from None
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
    """A GET for `path?query`, flagged so @run_page neither logs it nor acts on it.

    The whole page is rendered, not an htmx fragment: the shell has live regions too (its
    clock), and only the recorded regions are sent, so the rest costs little.
    """
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
        "CSRF_COOKIE": _PLACEHOLDER_SECRET,
    }
    request_attrs.make_live(request, HtmxDetails(request))  # its regions filled by the tag
    return request


def render_page(run: Run, url: str, host: str = "testserver") -> HttpRequest:
    """Render the page at `url` of `run` by its own view as a live (side-effect-free) request;
    the request comes back holding what the render recorded (its regions, its page)."""
    path, query = page_path_for(run, url)
    try:
        match = resolve(path)
    except Resolver404:
        raise NotLive("no page at this URL") from None
    if match.kwargs.get("token") != run.token:
        raise NotLive("the URL is not a page of this run")
    if not getattr(match.func, LIVE_PAGE, False):
        raise NotLive("the URL is not a page with live regions (a live render never acts)")
    request = live_request(path, query, host)
    try:
        response = match.func(request, *match.args, **match.kwargs)
    except Http404 as exc:  # the run closed, or the open item was purged meanwhile
        raise NotLive(f"the page is gone: {exc}") from None
    if hasattr(response, "render"):
        response.render()
    if response.status_code != 200:
        raise NotLive(f"the page answered {response.status_code}")
    return request


@dataclass(frozen=True)
class LiveUpdate:
    url: str  # the page URL rendered (the client ignores updates for a page it has left)
    seq: int  # the log position the render includes at least
    html: str  # out-of-band swaps, CSRF token values blank (the client fills in its own)
    # Simulated time at which what the render shows next changes with the clock (None: never).
    next_change: float | None = None
    regions: tuple[tuple[str, str], ...] = ()  # (id, outer HTML) as recorded, in page order

    def message(self) -> dict:
        # "html" last: bench_live reads the header of a frame without parsing the HTML.
        return {
            "type": "regions",
            "url": self.url,
            "seq": self.seq,
            "next_change": self.next_change,
            "html": self.html,
        }

    @cached_property
    def text(self) -> str:
        """The message as one JSON frame, encoded once for all subscribers."""
        return json.dumps(self.message())

    @cached_property
    def looks(self) -> str:
        """What a person sees of the regions (text, clock, pictures): a push that would not
        change it is not sent (apps.kit.consumers)."""
        return visible_signature(self.html)

    def position(self) -> dict:
        """The frame that moves a page's log position and due time without touching it: the
        log grew, but nothing the page shows changed."""
        return {**self.message(), "html": ""}

    def shows(self, seq: int, now: float) -> bool:
        """Is this render what a fresh one at log position `seq`, simulated time `now` gives?"""
        return self.seq >= seq and (self.next_change is None or now < self.next_change)


def render_update(run: Run, url: str, host: str = "testserver") -> LiveUpdate:
    """Render `url` now and collect its live regions (sync: call from a worker thread)."""
    seq = last_live_seq(run.pk)
    request = render_page(run, url, host)
    regions = tuple(request_attrs.live_regions(request))
    page = request_attrs.page(request)
    if page is not None:
        seq = max(seq, page.live_seq)  # the render may have fired what was due itself
    # Verbatim, whitespace between tags included: a browser draws "\n    " and " " alike,
    # but an agent reading the page's text or markup would see a change where none was.
    html = "\n".join(outer for _, outer in regions)
    return LiveUpdate(
        url=url,
        seq=seq,
        html=without_csrf_tokens(html),
        next_change=None if page is None else page.next_change,
        regions=regions,
    )


# One render per (run, URL, log position, clock window) for the whole process: sockets on the
# event loop and polls in request threads share it. Striped locks make concurrent askers for the
# same page wait for one render instead of doing their own.
RENDERS_KEPT = 256
_renders: LRU[tuple[int, str], LiveUpdate] = LRU(RENDERS_KEPT)
_render_locks = tuple(threading.Lock() for _ in range(64))


def shared_render(run: Run, url: str, seq: int, now: float, host: str = "testserver") -> LiveUpdate:
    """The live regions of `url` as of log position `seq` (at least) and simulated time `now`,
    reusing a render that shows the same (sync)."""
    key = (run.pk, url)
    cached = _renders.get(key)
    if cached is not None and cached.shows(seq, now):
        return cached
    with _render_locks[hash(key) % len(_render_locks)]:
        cached = _renders.get(key)
        if cached is not None and cached.shows(seq, now):
            return cached
        update = render_update(run, url, host)
        _renders.put(key, update, unless=lambda kept: kept.seq > update.seq)
        return update


async def shared_update(
    run: Run, url: str, seq: int, now: float, host: str = "testserver"
) -> LiveUpdate:
    """`shared_render` for the event loop: a reusable render costs no thread hop."""
    from channels.db import database_sync_to_async

    cached = _renders.get((run.pk, url))
    if cached is not None and cached.shows(seq, now):
        return cached
    return await database_sync_to_async(_socket_render)(run, url, seq, now, host)


def _socket_render(run: Run, url: str, seq: int, now: float, host: str) -> LiveUpdate:
    """`shared_render`, with what every socket reads of it — its signature and its frame —
    worked out here in the thread, once: on the event loop, reading MicroMail's 300 KB inbox
    held every other socket and request for milliseconds."""
    update = shared_render(run, url, seq, now, host)
    _ = update.looks, update.text  # cached on the shared render
    return update


def open_run(token: str) -> Run | None:
    close_old_connections()
    return Run.objects.open_by_token(token)
