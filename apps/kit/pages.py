"""What every environment page view needs: the run behind the URL, its state *now*, the clock.

`@run_page` resolves `/r/<token>/…` to an open run (404 otherwise), fires what is due (zero
staleness), folds the state, logs the page view, and hands the view a `Page`. Environment views
stay thin: they read `page.state`, call `page.act(...)` for actions, and render.

A *live* request (`request.sentinel_live`, made by apps.kit.live to re-render a page's live regions
for a websocket push or a poll) is a pure read: no view event is logged and `page.act` refuses,
so implicit effects (opening marks read) never happen behind the user's back.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import cached_property, wraps
from typing import Any

from django.http import Http404, HttpRequest, HttpResponse, HttpResponseNotAllowed
from django.shortcuts import render
from django.views.decorators.http import require_GET, require_POST

from apps.kit import links, request_attrs
from apps.kit.live import renderable
from apps.kit.query import InvalidQuery
from events.clock import sim_now, sim_rate, wall_now
from events.commands import current_folded, has_room, perform_action, record_view
from events.models import Event, Run
from events.projection import Folded, past_view, state_at
from events.registry import ActionRejected, Environment, get_environment


class LiveRenderActed(ActionRejected):
    """A view tried to act while being re-rendered for a live push: refused, nothing logged."""

    def __init__(self) -> None:
        super().__init__("a live re-render never acts", status=409)


@dataclass(frozen=True)
class Probe:
    """A page rendered on a state folded in memory, at simulated second `at`, for a run that
    need not be stored (apps.kit.probe): read-only like time travel, nothing logged or done."""

    run: Run
    state: Any
    at: float
    root: str


AGE_REFRESH_S = 60.0  # simulated seconds; whole minutes, as the shell's clock turns over


def run_for_token(token: str) -> Run:
    run = Run.objects.open_by_token(token)
    if run is None:
        raise Http404("no open run with this token")
    return run


ARRIVAL = "sentinel.arrived_at"  # ASGI scope key: wall time the request reached the server


def arrival_wall(request: HttpRequest) -> float:
    """The wall time the request arrived, stamped by the server before it waited for a request
    thread (sentinel_site/http_handler.py), so a busy server does not make an agent look slow;
    now, for a request that did not come through it (the test client)."""
    scope = getattr(request, "scope", None)
    arrived = scope.get(ARRIVAL) if isinstance(scope, dict) else None
    return arrived if arrived is not None else wall_now()


@dataclass
class Page:
    request: HttpRequest
    run: Run
    state: Any
    now: float  # simulated seconds (authored scale): the request's one clock reading
    wall: float = 0.0  # the wall time `now` was read at (actions are logged at that moment)
    live: bool = False  # a side-effect-free re-render for a live push (see module docstring)
    # Log position of the last scenario/action event the state includes (at least): the live
    # client starts from it, so an event fired between render and subscription is still pushed.
    live_seq: int = 0
    # Time travel (the staff-only replay viewer in apps.replay) renders a past log position:
    # nothing is logged or performed, and links stay under the viewer's own URL prefix.
    read_only: bool = False
    base: str | None = None
    # The earliest simulated time after `now` at which something this page shows changes
    # without any event (a relative time ticks over, a price moves): live pages are re-rendered
    # and pushed then. None: nothing shown depends on the clock.
    next_change: float | None = None
    # The earliest simulated time after `now` at which a fresh render (a reload) would read
    # differently; before `next_change` when a value moves that the product only refreshes
    # every few minutes on an open page (`refreshes_at`). None: same as `next_change`.
    fresh_until: float | None = None
    # The fold `state` comes from (None for time travel): an action is decided on it and
    # applied to it, so a page action fires and folds nothing more (events.commands).
    folded: Folded | None = None

    @property
    def live_socket(self) -> str:
        """Websocket path pushing this page's live regions (see apps.kit.consumers)."""
        return links.live_path(self.run)

    @cached_property
    def environment(self) -> Environment[Any]:
        """The environment this page belongs to (its title, actions…)."""
        return get_environment(self.run.environment)

    @cached_property
    def root(self) -> str:
        """URL prefix of this run's pages for the environment: /r/<token>/<env>."""
        return self.base or links.environment_root(self.run)

    def changes_at(self, at: float | None) -> None:
        """Note that what this page shows changes at simulated second `at` (None: never)."""
        if at is not None and (self.next_change is None or at < self.next_change):
            self.next_change = max(at, self.now)
        self._fresh_until(at)

    def refreshes_at(self, at: float | None, every: float) -> None:
        """A value shown moves at `at`, but an open page picks it up only at the product's next
        refresh (every `every` simulated seconds: a video feed's view counts), not live: a
        reload shows it at once, a live push waits for the refresh."""
        if at is None:
            return
        self._fresh_until(at)
        boundary = (self.now // every + 1) * every
        self.changes_at_live(max(at, boundary))

    def ages_at(self, at: float | None) -> None:
        """A relative time shown ("5 min ago") next reads differently at `at`: an open page
        takes it up with the clock's next minute, so a feed's ages and the top bar's clock move
        together, once a minute, never at every item's own second."""
        self.refreshes_at(at, AGE_REFRESH_S)

    def changes_at_live(self, at: float | None) -> None:
        if at is not None and (self.next_change is None or at < self.next_change):
            self.next_change = max(at, self.now)

    def note_changes(self, fresh_until: float | None, live_due: float | None) -> None:
        """What a kept render of this page noted (apps.kit.screen_cache)."""
        self._fresh_until(fresh_until)
        self.changes_at_live(live_due)

    def _fresh_until(self, at: float | None) -> None:
        if at is not None and (self.fresh_until is None or at < self.fresh_until):
            self.fresh_until = max(at, self.now)

    @property
    def reads_same_until(self) -> float | None:
        """Until when a reload reads like this render (the screen cache keeps it that long)."""
        if self.fresh_until is None:
            return self.next_change
        if self.next_change is None:
            return self.fresh_until
        return min(self.fresh_until, self.next_change)

    def act(self, action: str, payload: dict) -> Event | None:
        """Perform an agent action; the state is refreshed so the response shows its effect.

        A read-only (time travel) page performs nothing and returns None: implicit effects such
        as "opening marks read" are not applied to the past.
        """
        if self.read_only:
            return None
        if self.live:
            raise LiveRenderActed()
        event, folded = perform_action(
            self.run, action, payload, wall=self.wall, folded=self.folded
        )
        # The live client starts after the action: its own push is not sent back to it.
        self.folded, self.state, self.live_seq = folded, folded.state, folded.live_seq
        return event


def one_of(name: str, allowed, what: str) -> str:
    """`name` when it is one of `allowed` (a URL segment naming an action, a tab…), else a 404
    page naming what was asked for and what exists."""
    if name not in allowed:
        raise ActionRejected(f"unknown {what} {name!r}; allowed: {', '.join(allowed)}", 404)
    return name


def chosen(name: str, value: str, allowed: Sequence[str]) -> str:
    """`value` of the form field or URL parameter `name` when it is one of `allowed`, else a 400
    page naming them (the message `QueryState` gives a URL's choices)."""
    if value not in allowed:
        raise ActionRejected(f"{name}={value!r} is not valid; allowed: {', '.join(allowed)}")
    return value


def is_navigation(request: HttpRequest) -> bool:
    """A page the user goes to (a load, a boosted link), not a fragment refreshed in place."""
    htmx = getattr(request, "htmx", None)
    return request.method == "GET" and (not htmx or htmx.boosted)


def perform_implicit_actions(request: HttpRequest, page: Page, kwargs: dict) -> None:
    """Opening a page does what opening it does in the real product (declared per environment:
    `Environment.implicit_actions`), once — reloading an opened item changes nothing."""
    if page.live or page.read_only or not is_navigation(request):
        return
    match = getattr(request, "resolver_match", None)
    url_name = match.url_name if match is not None else None
    for implicit in get_environment(page.run.environment).implicit_actions:
        if implicit.page != url_name:
            continue
        value = kwargs.get(implicit.param) or request.GET.get(implicit.param)
        if value and implicit.applies(page.state, value):
            page.act(implicit.action, implicit.payload(value))


def rejected(
    request: HttpRequest, page: Page, exc: ActionRejected, *, missing: bool = False
) -> HttpResponse:
    """A refused page or action, or a page of the run that does not exist, as a page of the
    site naming the reason (with JavaScript on, the shell swaps it in like any page:
    static/site/shell.js)."""
    context = {
        "page": page,
        "missing": missing,  # the page itself does not exist (not an action refused)
        "message": str(exc),
        "back": page.root + "/",
        "environment_title": page.environment.title,
    }
    return render(request, "site/rejected.html", context, status=exc.status)


def run_page(view: Callable[..., HttpResponse]) -> Callable[..., HttpResponse]:
    @wraps(view)
    def wrapper(request: HttpRequest, token: str, *args, **kwargs) -> HttpResponse:
        past = getattr(request, "sentinel_time_travel", None)
        if past is not None:
            # Set only by the staff-only admin viewer (apps.replay) and by a probe render
            # (apps.kit.probe), never by a /r/ URL.
            if request.method != "GET":
                return HttpResponseNotAllowed(["GET"])
            # A probe (apps.kit.probe) brings the state it folded in memory; the replay viewer
            # names a log position of a stored run.
            state = past.state if isinstance(past, Probe) else state_at(past.run, past.seq)
            page = Page(
                request=request,
                run=past.run,
                state=state,
                now=past.at,
                read_only=True,
                base=past.root,
            )
            request_attrs.set_page(request, page)
            return view(request, page, *args, **kwargs)
        run = run_for_token(token)
        if not request.path.startswith(links.environment_root(run) + "/"):
            # Another environment's page under this run's token would render its views on
            # a state they do not know.
            raise Http404(f"this run plays {run.environment}: no such page")
        wall = arrival_wall(request)  # the one clock reading of this request
        folded = current_folded(run, wall=wall, reload=False)  # the run was read just now
        live = bool(getattr(request, "sentinel_live", False))
        page = Page(
            request=request,
            run=run,
            state=folded.state,
            now=sim_now(run, wall),
            wall=wall,
            live=live,
            live_seq=folded.live_seq,
            folded=folded,
        )
        request_attrs.set_page(request, page)  # what a live render reads back (apps.kit.live)
        request_attrs.set_sim_clock(request, page.now, sim_rate(run, page.now))
        try:
            if request.method == "GET" and not live and has_room(run, folded):
                viewed = record_view(
                    run,
                    request.get_full_path(),
                    at=page.now,
                    partial=bool(getattr(request, "htmx", False)),
                )
                page.folded = past_view(folded, viewed)
            perform_implicit_actions(request, page, kwargs)
            return view(request, page, *args, **kwargs)
        except ActionRejected as exc:
            return rejected(request, page, exc)
        except InvalidQuery as exc:  # a view's QueryState.from_params: a page naming the field
            return rejected(request, page, ActionRejected(str(exc), exc.status))
        except Http404 as exc:  # an item the run does not show (unknown or not arrived yet)
            reason = ActionRejected(str(exc) or "no such page", 404)
            return rejected(request, page, reason, missing=True)

    return renderable(wrapper)  # the only views the live protocol renders


def screen_view(view: Callable[..., HttpResponse]) -> Callable[..., HttpResponse]:
    """A screen of the run: `@run_page`, answering GET only."""
    return require_GET(run_page(view))


def form_view(view: Callable[..., HttpResponse]) -> Callable[..., HttpResponse]:
    """Where a form posts: `@run_page`, answering POST only (the view acts, then redirects)."""
    return require_POST(run_page(view))
