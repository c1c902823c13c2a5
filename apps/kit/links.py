"""Where a run's pages live. Everything an agent reaches is under the run's prefix on our own
site; the prefix itself is spelled once (`RUN_PREFIX` in sentinel_site/urls.py) and every URL
here is `reverse()`d from it."""

from __future__ import annotations

import functools

from django.urls import reverse

from events.models import Run

HOST_PLACEHOLDER = "HOST_ADDRESS"


def site_root(run: Run) -> str:
    """/r/<token> (no trailing slash)."""
    return _site_root(run.token)


@functools.lru_cache(maxsize=4096)  # every page asks several times; reverse() is not free
def _site_root(token: str) -> str:
    return reverse("run-home", kwargs={"token": token}).rstrip("/")


def environment_root(run: Run) -> str:
    """Where the run's environment pages live: /r/<token>/<env>."""
    return f"{site_root(run)}/{run.environment}"


def live_path(run: Run) -> str:
    """The websocket (and polling) endpoint of the run's live pages (apps.kit.consumers)."""
    return _live_path(run.token)


@functools.lru_cache(maxsize=4096)
def _live_path(token: str) -> str:
    return reverse("live-poll", kwargs={"token": token})


def start_page_path(run: Run) -> str:
    """The scenario's start page on our site (`HOST_ADDRESS/<env>` → `/r/<token>/<env>`)."""
    start_page = run.spec.get("start_page") or f"{HOST_PLACEHOLDER}/{run.environment}"
    path = start_page.replace(HOST_PLACEHOLDER, site_root(run))
    if not path.startswith(site_root(run)):
        # Never redirect off-site: a start page must be one of the run's own pages.
        path = environment_root(run)
    return path


def contact_path(run: Run) -> str:
    return reverse("run-contact", kwargs={"token": run.token})


def wait_path(run: Run) -> str:
    """Where the agent of a fast_forward run declares its waits (apps.control.agent.run_wait)."""
    return reverse("run-wait", kwargs={"token": run.token})


def task_path(run: Run) -> str:
    return reverse("run-start", kwargs={"token": run.token})
