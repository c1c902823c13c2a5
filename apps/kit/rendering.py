"""Rendering an environment's pages: one view serves the whole page and its htmx fragment, and
an action answers with post/redirect/get.

An environment's templates extend `base_template`: its own `<env>/base.html` (the shell with the
environment's chrome) for a page, or `site/fragment.html` (the content block alone) when htmx
asks for a fragment — a non-boosted htmx request, e.g. a region refreshed in place.
"""

from __future__ import annotations

from typing import Any
from urllib.parse import urlsplit

from django.contrib import messages
from django.http import HttpRequest, HttpResponse, HttpResponseRedirect
from django.template.loader import render_to_string

from apps.kit import request_attrs, screen_cache
from apps.kit.pages import Page

FRAGMENT_TEMPLATE = "site/fragment.html"


def is_fragment(request: HttpRequest) -> bool:
    htmx = request_attrs.htmx(request)
    return bool(htmx and not htmx.boosted)


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


def redirect_after(
    request: HttpRequest, page: Page, path: str = "", done: str = ""
) -> HttpResponse:
    """Post/redirect/get after an action, with `done` shown once as a toast (when given)."""
    if done:
        messages.success(request, done)
    return redirect_to(page, path)


def _on_site(path: str) -> bool:
    return not (path.startswith("/") or "://" in path or "\\" in path)


def back_field(request: HttpRequest, default: str = "") -> str:
    """Where a form says to return: its `back` field, a path relative to the environment root
    (anything absolute is ignored, so a form can never redirect off the site), else `default`."""
    back = request.POST.get("back", default)
    return back if _on_site(back) else default


def came_from(request: HttpRequest, page: Page, default: str = "") -> str:
    """The screen a form was on, relative to the environment root: its Referer when that is one
    of this run's environment pages, else `default`."""
    referer = urlsplit(request.headers.get("referer", ""))
    prefix = page.root + "/"
    if not referer.path.startswith(prefix):
        return default
    return referer.path[len(prefix) :] + (f"?{referer.query}" if referer.query else "")
