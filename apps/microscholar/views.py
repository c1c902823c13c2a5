"""MicroScholar pages: thin views over `page.state`, actions through `page.act`.

Each view serves the whole page, or its content block for an htmx fragment request
(apps.kit.rendering). Actions are POST forms that go back to the screen they came from
(`back`, post/redirect/get). Opening the Cite dialog cites the paper: declared with the
environment (`implicit_actions`), so this module never does it itself.
"""

from __future__ import annotations

from collections.abc import Callable

from django.http import Http404, HttpRequest, HttpResponse
from django.views.decorators.http import require_POST

from apps.kit import simclock
from apps.kit.pages import Page, run_page, screen_view
from apps.kit.rendering import back_field, redirect_after, render_screen
from apps.kit.retractions import is_gone
from apps.kit.streaming import COUNT_REFRESH_S, present
from apps.microscholar import cite as citing
from apps.microscholar import screens
from apps.microscholar import state as index
from apps.microscholar.actions import existing_paper
from apps.microscholar.catalog import profiles
from apps.microscholar.query import AlertsQuery, ProfileQuery, SearchQuery
from apps.microscholar.state import Scholar


def root_url(page: Page) -> str:
    return page.root + "/"


def this_year(page: Page) -> int:
    """The simulated calendar year (the "Since <year>" filters follow it)."""
    return simclock.moment(page.now, simclock.day_zero(page.run)).year


def show(
    request: HttpRequest, page: Page, template: str, current: str, back: str, **context
) -> HttpResponse:
    """The template `template` with what its chrome needs: the `current` tab, the library and
    alerts badges, "My profile", and `back` (where its forms come back to)."""
    scholar = page.state
    me = screens.my_profile_id(scholar)
    chrome = {
        "current": current,
        "library_count": index.saved_paper_count(scholar),
        "unread_alerts": index.unread_alert_count(scholar),
        "my_profile_url": screens.profile_url(root_url(page), me) if me else None,
        "back": back,
    }
    return render_screen(request, page, f"microscholar/{template}.html", chrome | context)


def watch(page: Page, ids) -> None:
    """The page changes when a shown "Cited by" count next ticks over; an open page takes it up
    at its next refresh (Google Scholar's counts never move under the reader's eyes)."""
    papers = page.state.papers
    changes = (papers[i].citations_change_at(page.now) for i in ids)
    page.refreshes_at(min((t for t in changes if t is not None), default=None), COUNT_REFRESH_S)


def shown_rows(page: Page, ids) -> tuple[screens.Row, ...]:
    watch(page, ids)
    return screens.rows(page.state, ids, page.now, root_url(page))


def shown_paper(page: Page, paper_id: str):
    return present(page.state.papers.get(paper_id), "paper")  # unknown, not indexed yet: alike


def citable_paper(page: Page, paper_id: str):
    """A paper to cite or export: a withdrawn one's page says so, and it has no citation."""
    found = shown_paper(page, paper_id)
    if is_gone(found):
        raise Http404(f"paper {paper_id!r} was withdrawn by its authors")
    return found


@screen_view
def search(request: HttpRequest, page: Page) -> HttpResponse:
    """Home (recommended articles) without `q`; results with the filter column with it."""
    query = SearchQuery.from_params(request.GET).check()
    screen = screens.search_screen(page.state, query, this_year(page), root_url(page))
    return show(
        request,
        page,
        "results" if query.q else "home",
        "search" if query.q else "home",
        query.querystring(),
        screen=screen,
        query=query,
        rows=shown_rows(page, screen.ids),
    )


def show_paper(request: HttpRequest, page: Page, paper_id: str, template: str, **context):
    """The paper's page (`template` "paper", or "cite" with the dialog open) and its related."""
    shown_paper(page, paper_id)
    watch(page, [paper_id])
    paper = screens.row(page.state, paper_id, page.now, root_url(page), full=True)
    related = shown_rows(page, screens.related(page.state, paper_id))
    back = f"papers/{paper_id}"
    return show(request, page, template, "paper", back, paper=paper, related=related, **context)


@screen_view
def paper(request: HttpRequest, page: Page, paper_id: str) -> HttpResponse:
    return show_paper(request, page, paper_id, "paper")


@screen_view
def cite(request: HttpRequest, page: Page, paper_id: str) -> HttpResponse:
    """The paper's page with the Cite dialog open: five styles and the export links."""
    found = citable_paper(page, paper_id)
    names = citing.author_names(found, page.state.catalog)
    styles = citing.styles(found, names)
    exports = [(fmt, label) for fmt, (label, _, _) in citing.EXPORTS.items()]
    return show_paper(request, page, paper_id, "cite", styles=styles, exports=exports)


@screen_view
def export(request: HttpRequest, page: Page, paper_id: str, fmt: str) -> HttpResponse:
    """A citation file to download (the request is logged like every page view)."""
    found = citable_paper(page, paper_id)
    if fmt not in citing.EXPORTS:
        raise Http404(f"format={fmt!r} is not valid; allowed: {', '.join(citing.EXPORTS)}")
    _, extension, media_type = citing.EXPORTS[fmt]
    body = citing.export(found, citing.author_names(found, page.state.catalog), fmt)
    response = HttpResponse(body, content_type=f"{media_type}; charset=utf-8")
    response["Content-Disposition"] = f'attachment; filename="{paper_id}.{extension}"'
    return response


@screen_view
def profile(request: HttpRequest, page: Page) -> HttpResponse:
    query = ProfileQuery.from_params(request.GET)
    if not query.user:
        me = screens.my_profile_id(page.state)
        if me is None:
            raise Http404("no profile for the signed-in user")
        query = query.but(user=me)
    if query.user not in page.state.catalog.index(profiles):
        raise Http404("no such scholar")
    screen = screens.profile_screen(page.state, query, page.now, this_year(page), root_url(page))
    watch(page, screens.authored(page.state, query.user))
    return show(
        request, page, "profile", "profile", "citations" + query.querystring(), screen=screen
    )


@screen_view
def library(request: HttpRequest, page: Page) -> HttpResponse:
    rows = shown_rows(page, screens.library(page.state))
    return show(request, page, "library", "library", "library", rows=rows)


@screen_view
def alerts(request: HttpRequest, page: Page) -> HttpResponse:
    query = AlertsQuery.from_params(request.GET)
    screen = screens.alerts_screen(page.state, query, root_url(page))
    return show(request, page, "alerts", "alerts", "alerts" + query.querystring(), screen=screen)


def posting(action: str, field: str, done: Callable[[Scholar, str], str]):
    """A form's POST view: perform `action` on the item named by the form's `field`, then back to
    the screen the form was on (`back`, relative to the root; never off-site) with `done`."""

    @require_POST
    @run_page
    def view(request: HttpRequest, page: Page) -> HttpResponse:
        item_id = request.POST.get(field, "")
        page.act(action, {field: item_id})
        return redirect_after(request, page, back_field(request), done(page.state, item_id))

    return view


def _library(verb: str) -> Callable[[Scholar, str], str]:
    return lambda scholar, paper_id: f"{verb} My library: {existing_paper(scholar, paper_id).title}"


save = posting("save", "paper_id", _library("Saved to"))
remove = posting("unsave", "paper_id", _library("Removed from"))
mark_alert_read = posting("mark_alert_read", "alert_id", lambda scholar, _: "Alert marked as read")
