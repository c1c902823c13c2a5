"""Render an environment page on a state folded in memory, without a stored run.

What a scenario check needs to see a page as an agent would at a given simulated moment
(apps.scenarios.watching) without creating a run, logging a view or touching the database:
the environment's own view, through `@run_page`, read-only like the replay viewer.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from datetime import UTC, datetime
from typing import Any

from django.urls import Resolver404, resolve

from apps.kit import links
from apps.kit.pages import Probe
from events.catalog import load_catalog
from events.models import Run
from events.registry import EMPTY, LoggedEvent, get_environment

# What @run_page reads for a page of the past (apps.replay) or, here, of a folded state.
TIME_TRAVEL = "sentinel_time_travel"
PROBE_TOKEN = "probe"  # never a stored run's token (those are long random strings)


class NotRendered(Exception):
    """The page could not be rendered (unknown path, an error page): the message says why."""


def probe_run(environment: str, spec: dict[str, Any], *, day_zero: datetime | None = None) -> Run:
    """An unsaved run of `environment` playing `spec`, only for rendering its pages."""
    created = day_zero or datetime(2025, 1, 6, tzinfo=UTC)
    return Run(token=PROBE_TOKEN, environment=environment, scenario=spec, created_at=created)


def state_at_time(
    environment: str,
    events: Iterable[Mapping[str, Any]],
    at: float,
    *,
    event_timeline_end: float = float("inf"),
    catalog_dir=None,
) -> Any:
    """The state a run of the timeline `events` ({time, type, payload}, in order) has at
    simulated second `at`, folded in memory as the engine folds a log (nothing stored)."""
    env = get_environment(environment)
    logged = [
        LoggedEvent(seq, float(e["time"]), "scenario", e["type"], e.get("payload") or {})
        for seq, e in enumerate(events, 1)
        if float(e["time"]) <= min(at, event_timeline_end)
    ]
    state, _ = env.fold(env.initial_state(load_catalog(catalog_dir)), logged, EMPTY)
    return state


def environment_path(page_url: str, environment: str) -> str:
    """A scenario page (`HOST_ADDRESS/<env>/jobs?x=1#week`) as a path under the environment
    root (`jobs?x=1`); the fragment is the browser's business."""
    url = page_url.split("#", 1)[0]
    prefix = f"{links.HOST_PLACEHOLDER}/{environment}"
    if not url.startswith(prefix):
        raise NotRendered(f"{page_url!r} is not a page of {environment} ({prefix}/…)")
    return url[len(prefix) :].lstrip("/")


def render_probe(run: Run, state: Any, at: float, path: str) -> str:
    """The HTML of page `path` (relative to the environment root) showing `state` at simulated
    second `at`."""
    environment = get_environment(run.environment)
    page = path.partition("?")[0]
    try:
        match = resolve("/" + page, urlconf=environment.urlconf)
    except Resolver404:
        raise NotRendered(f"no page {path!r} in {run.environment}") from None
    root = links.environment_root(run)
    # django.test pulls in unittest: loaded when a page is probed, not by every process that
    # loads the admin (which reaches this module through the scenario checks).
    from django.test import RequestFactory

    request = RequestFactory().get(f"{root}/{path}")
    setattr(request, TIME_TRAVEL, Probe(run=run, state=state, at=at, root=root))
    response = match.func(request, run.token, *match.args, **match.kwargs)
    if hasattr(response, "render") and not getattr(response, "is_rendered", True):
        response = response.render()
    if response.status_code != 200:
        raise NotRendered(f"{run.environment} page {path!r} answered {response.status_code}")
    return response.content.decode(response.charset or "utf-8")
