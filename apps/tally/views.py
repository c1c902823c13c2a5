"""Tally pages: one screen, one form. Thin views over `page.state`, the action by `page.act`."""

from __future__ import annotations

from django.contrib import messages
from django.http import HttpRequest, HttpResponse

from apps.kit.pages import Page, form_view, screen_view
from apps.kit.rendering import redirect_to, render_screen
from events.registry import ActionRejected


@screen_view
def tally(request: HttpRequest, page: Page) -> HttpResponse:
    """The tally, with the level as of the page's `now` (re-rendered when its shown value moves)."""
    state = page.state
    page.changes_at(state.level_changes_at(page.now))
    context = {"token": page.run.token, "tally": state, "level": state.shown_level(page.now)}
    return render_screen(request, page, "tally/tally.html", context)


def typed_count(request: HttpRequest) -> int:
    text = request.POST.get("n", "").strip()
    try:
        return int(text)
    except ValueError:
        raise ActionRejected(f"n must be a whole number, got {text!r}") from None


@form_view
def poke(request: HttpRequest, page: Page) -> HttpResponse:
    """`POST poke` with `n`, then back to the tally (post/redirect/get)."""
    n = typed_count(request)
    page.act("poke", {"n": n})
    messages.success(request, f"Poked {n}")
    return redirect_to(page)
