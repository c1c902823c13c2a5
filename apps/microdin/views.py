"""MicroDin pages: thin views over `page.state` (screens.py says what each shows), actions
through `page.act`, post/redirect/get back to the screen the form was on.

Every view serves the full page, or just its content when htmx asks for a fragment
(apps.kit.rendering). Opening a thread marks it read: declared with the environment
(`implicit_actions`), not done here.
"""

from __future__ import annotations

from django.http import Http404, HttpRequest, HttpResponse
from django.views.decorators.http import require_GET, require_POST

from apps.kit.pages import Page, run_page
from apps.kit.post_actions import act_on_post
from apps.kit.rendering import (
    back_field,
    came_from,
    redirect_after,
    render_screen,
)
from apps.microdin import screens
from apps.microdin.query import (
    JobsQuery,
    MessagingQuery,
    NotificationsQuery,
    SearchQuery,
)
from apps.microdin.state import SECTION_TYPES, Network, connections_count
from events.registry import ActionRejected

POST_ACTIONS = {"like_post": "", "unlike_post": "", "comment_post": "Comment posted"}
NOTIFICATION_FILTER_LABELS = (
    ("all", "All"),
    ("unread", "Unread"),
    ("posts", "My posts"),
    ("mentions", "Mentions"),
    ("jobs", "Jobs"),
)
SEARCH_KIND_LABELS = (
    ("all", "All"),
    ("people", "People"),
    ("companies", "Companies"),
    ("jobs", "Jobs"),
)
INVITATION_VERBS = {"accept": "accept_connection", "ignore": "ignore_connection"}


def base_context(page: Page, tab: str) -> dict:
    network: Network = page.state
    return {
        "token": page.run.token,
        "me": network.me,
        "tab": tab,
        "badges": screens.nav_badges(network),
    }


def show(request: HttpRequest, page: Page, template: str, tab: str, **context) -> HttpResponse:
    return render_screen(
        request, page, f"microdin/{template}", {**base_context(page, tab), **context}
    )


def ending(query, item: str) -> str:
    """The screen's query string without its open item, ready for `<item>=…` to be appended."""
    rest = query.but(**{item: None}).querystring()
    return rest + "&" if rest else "?"


# --- home feed and posts -----------------------------------------------------------------------


@require_GET
@run_page
def feed(request: HttpRequest, page: Page) -> HttpResponse:
    network = page.state
    return show(
        request,
        page,
        "feed.html",
        "home",
        cards=screens.feed(network),
        news=screens.news(network.catalog),
        follow=screens.feed_suggestions(network),
        stats=network.stats,
        connections_count=connections_count(network),
    )


@require_GET
@run_page
def post(request: HttpRequest, page: Page, post_id: str) -> HttpResponse:
    if post_id not in page.state.posts:
        raise Http404("no such post")  # unknown or not posted yet: alike
    card = screens.post_card(page.state, post_id)
    return show(request, page, "post.html", "home", cards=(card,), card=card)


@require_POST
@run_page
def post_action(request: HttpRequest, page: Page, post_id: str, action: str) -> HttpResponse:
    done = act_on_post(request, page, post_id, action, POST_ACTIONS)
    return redirect_after(request, page, came_from(request, page) + f"#post-{post_id}", done)


# --- my network ----------------------------------------------------------------------------------


@require_GET
@run_page
def my_network(request: HttpRequest, page: Page) -> HttpResponse:
    network = page.state
    pending = screens.invitations(network)
    return show(
        request,
        page,
        "network.html",
        "network",
        invitations=pending[: screens.INVITATIONS_PREVIEW],
        pending=len(pending),
        suggestions=screens.suggestions(network),
        connections=len(screens.connected_people(network)),
    )


@require_GET
@run_page
def invitations(request: HttpRequest, page: Page) -> HttpResponse:
    pending = screens.invitations(page.state)
    return show(
        request,
        page,
        "invitations.html",
        "network",
        invitations=pending,
        pending=len(pending),
        connections=len(screens.connected_people(page.state)),
    )


@require_GET
@run_page
def connections(request: HttpRequest, page: Page) -> HttpResponse:
    return show(
        request,
        page,
        "connections.html",
        "network",
        people=screens.connected_people(page.state),
        pending=len(screens.invitations(page.state)),
    )


@require_POST
@run_page
def answer_invitation(request: HttpRequest, page: Page, verb: str) -> HttpResponse:
    action = INVITATION_VERBS.get(verb)
    if action is None:
        raise ActionRejected(f"unknown answer {verb!r}; allowed: accept, ignore", 404)
    connection_id = request.POST.get("connection_id", "")
    page.act(action, {"connection_id": connection_id})
    name = page.state.connections[connection_id].person.name
    done = (
        f"You are now connected with {name}"
        if verb == "accept"
        else f"Invitation from {name} ignored"
    )
    return redirect_after(request, page, back_field(request, "mynetwork/"), done)


# --- jobs -------------------------------------------------------------------------------------------


@require_GET
@run_page
def jobs(request: HttpRequest, page: Page) -> HttpResponse:
    query = JobsQuery.from_params(request.GET)
    if query.job is not None and query.job not in page.state.jobs:
        raise Http404("no such job")
    screen = screens.jobs_screen(page.state, query)
    return show(
        request,
        page,
        "jobs.html",
        "jobs",
        screen=screen,
        query=query,
        list_query=ending(query, "job"),
    )


@require_POST
@run_page
def apply(request: HttpRequest, page: Page, job_id: str) -> HttpResponse:
    page.act("apply_job", {"job_id": job_id})
    job = page.state.jobs[job_id]
    back = back_field(request, "jobs/" + JobsQuery(job=job_id).querystring())
    return redirect_after(request, page, back, f"Application sent to {job.company.name}")


# --- messaging ---------------------------------------------------------------------------------------


@require_GET
@run_page
def messaging(request: HttpRequest, page: Page) -> HttpResponse:
    query = MessagingQuery.from_params(request.GET)
    if query.conversation is not None and query.conversation not in page.state.conversations:
        raise Http404("no such conversation")
    screen = screens.messaging_screen(page.state, query)
    return show(
        request,
        page,
        "messaging.html",
        "messaging",
        screen=screen,
        query=query,
        list_query=ending(query, "conversation"),
    )


@require_POST
@run_page
def send_message(request: HttpRequest, page: Page, conversation_id: str) -> HttpResponse:
    page.act(
        "send_message",
        {"conversation_id": conversation_id, "content": request.POST.get("content", "")},
    )
    return redirect_after(
        request, page, "messaging/" + MessagingQuery(conversation=conversation_id).querystring()
    )


@require_POST
@run_page
def start_conversation(request: HttpRequest, page: Page) -> HttpResponse:
    event = page.act("start_conversation", {"user_id": request.POST.get("user_id", "")})
    conversation_id = event.payload["conversation_id"] if event else ""
    return redirect_after(
        request, page, "messaging/" + MessagingQuery(conversation=conversation_id).querystring()
    )


# --- notifications ------------------------------------------------------------------------------------


@require_GET
@run_page
def notifications(request: HttpRequest, page: Page) -> HttpResponse:
    query = NotificationsQuery.from_params(request.GET)
    rows = screens.notifications_screen(page.state, query)
    return show(
        request,
        page,
        "notifications.html",
        "notifications",
        rows=rows,
        query=query,
        filters=NOTIFICATION_FILTER_LABELS,
    )


@require_POST
@run_page
def read_notification(request: HttpRequest, page: Page) -> HttpResponse:
    """Clicking a notification marks it read and goes to what it is about."""
    notification_id = request.POST.get("notification_id", "")
    page.act("mark_notification_read", {"notification_id": notification_id})
    notification = page.state.notifications[notification_id]
    return redirect_after(request, page, screens.notification_target(page.state, notification))


# --- profile, company, search ---------------------------------------------------------------------------


@require_GET
@run_page
def profile(request: HttpRequest, page: Page, user_id: str) -> HttpResponse:
    found = screens.profile(page.state, user_id)
    if found is None:
        raise Http404("no such member")
    return show(
        request,
        page,
        "profile.html",
        "me" if found.is_self else "",
        profile=found,
        section_types=SECTION_TYPES,
    )


@require_POST
@run_page
def add_section(request: HttpRequest, page: Page, user_id: str) -> HttpResponse:
    if user_id != page.state.me.id:
        raise ActionRejected("only your own profile can be edited", 403)
    payload = {k: request.POST.get(k, "") for k in ("type", "title", "subtitle", "content")}
    page.act("add_profile_section", payload)
    return redirect_after(request, page, f"in/{user_id}/", "Section added to your profile")


@require_GET
@run_page
def company(request: HttpRequest, page: Page, company_id: str) -> HttpResponse:
    found = screens.company_page(page.state, company_id)
    if found is None:
        raise Http404("no such company")
    return show(request, page, "company.html", "", company_page=found)


@require_GET
@run_page
def search(request: HttpRequest, page: Page) -> HttpResponse:
    query = SearchQuery.from_params(request.GET)
    results = screens.search(page.state, query)
    return show(
        request, page, "search.html", "", results=results, query=query, kinds=SEARCH_KIND_LABELS
    )
