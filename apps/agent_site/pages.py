"""What every environment page view needs: the run behind the URL, its state *now*, the clock.

`@run_page` resolves `/r/<token>/…` to an open run (404 otherwise), fires what is due (zero
staleness), folds the state, logs the page view, and hands the view a `Page`. Environment views
stay thin: they read `page.state`, call `page.act(...)` for actions, and render.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import wraps
from typing import Any

from django.http import Http404, HttpRequest, HttpResponse

from events.clock import sim_now, wall_now
from events.commands import current_state, perform_action, record_view
from events.models import Event, Run
from events.registry import ActionRejected


def run_for_token(token: str) -> Run:
    run = Run.objects.filter(token=token, closed_at__isnull=True).first()
    if run is None:
        raise Http404("no open run with this token")
    return run


@dataclass
class Page:
    request: HttpRequest
    run: Run
    state: Any
    now: float  # simulated seconds (authored scale), read once per request

    @property
    def root(self) -> str:
        """URL prefix of this run's pages for the environment: /r/<token>/<env>."""
        return f"/r/{self.run.token}/{self.run.environment}"

    def act(self, action: str, payload: dict) -> Event:
        """Perform an agent action; the state is refreshed so the response shows its effect."""
        event = perform_action(self.run, action, payload)
        self.state = current_state(self.run)
        return event


def run_page(view: Callable[..., HttpResponse]) -> Callable[..., HttpResponse]:
    @wraps(view)
    def wrapper(request: HttpRequest, token: str, *args, **kwargs) -> HttpResponse:
        run = run_for_token(token)
        state = current_state(run)
        page = Page(request=request, run=run, state=state, now=sim_now(run, wall_now()))
        if request.method == "GET":
            record_view(run, request.get_full_path(), partial=bool(getattr(request, "htmx", False)))
        try:
            return view(request, page, *args, **kwargs)
        except ActionRejected as exc:
            return HttpResponse(str(exc), status=exc.status, content_type="text/plain")

    return wrapper
