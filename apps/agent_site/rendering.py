"""Rendering an environment's pages: one view serves the whole page and its htmx fragment, and
an action answers with post/redirect/get.

An environment's templates extend `base_template`: its own `<env>/base.html` (the shell with the
environment's chrome) for a page, or `site/fragment.html` (the content block alone) when htmx
asks for a fragment — a non-boosted htmx request, e.g. a region refreshed in place.
"""

from __future__ import annotations

from typing import Any

from django.http import HttpRequest, HttpResponse, HttpResponseRedirect
from django.template.loader import render_to_string

from apps.agent_site import screen_cache
from apps.agent_site.pages import Page

FRAGMENT_TEMPLATE = "site/fragment.html"


def is_fragment(request: HttpRequest) -> bool:
    htmx = getattr(request, "htmx", None)
    return bool(htmx) and not htmx.boosted


def render_screen(
    request: HttpRequest,
    page: Page,
    template: str,
    context: dict[str, Any],
    *,
    status: int = 200,
) -> HttpResponse:
    """`template` with `page`, `root` and `base_template` in its context — or the same screen
    rendered for an earlier identical load, while nothing it shows can have changed
    (`screen_cache`)."""
    base = FRAGMENT_TEMPLATE if is_fragment(request) else f"{page.run.environment}/base.html"
    full = {"page": page, "root": page.root + "/", "base_template": base, **context}
    return screen_cache.cached_render(
        request, page, lambda extra: render_to_string(template, {**full, **extra}, request), status
    )


def redirect_to(page: Page, path: str = "") -> HttpResponse:
    """Post/redirect/get: back to `path` (relative to the environment root, e.g. "?folder=x")."""
    return HttpResponseRedirect(page.root + "/" + path)
