"""MicroDin pages: thin views over `page.state` (screens.py says what each shows), actions
through `page.act`, post/redirect/get back to the screen the form was on.

Every view serves the full page, or just its content when htmx asks for a fragment
(apps.kit.rendering). Opening a thread marks it read: declared with the environment
(`implicit_actions`), not done here.
"""

from __future__ import annotations

from django.http import HttpRequest, HttpResponse

from apps.kit import feed_views
from apps.kit.feed_views import FeedPages, act_on_post, open_thread, shown
from apps.kit.pages import Page, one_of
from apps.kit.rendering import back_field, came_from, redirect_after, redirect_to
from apps.kit.streaming import present
from apps.microdin import screens
from apps.microdin.query import (
    NOTIFICATION_FILTERS,
    SEARCH_KINDS,
    JobsQuery,
    MessagingQuery,
    NotificationsQuery,
    SearchQuery,
    job_path,
    thread_path,
)
from apps.microdin.state import SECTION_TYPES, Network, connections_count
from events.registry import ActionRejected

PAGES = FeedPages(badges=screens.nav_badges)
POST_ACTIONS = {"like_post": "", "unlike_post": "", "comment_post": "Comment posted"}
# (value, label) per chip: the value capitalised ("My posts": notifications about the user's).
NOTIFICATION_FILTER_LABELS = tuple(
    (name, "My posts" if name == "posts" else name.title()) for name in NOTIFICATION_FILTERS
)
SEARCH_KIND_LABELS = tuple((kind, kind.title()) for kind in SEARCH_KINDS)
INVITATION_VERBS = {"accept": "accept_connection", "ignore": "ignore_connection"}
ANSWERED = {"accept": "You are now connected with {}", "ignore": "Invitation from {} ignored"}


def ending(query, item: str) -> str:
    """The screen's query string without its open item, ready for `<item>=…` to be appended."""
    rest = query.but(**{item: None}).querystring()
    return rest + "&" if rest else "?"


# --- home feed and posts -----------------------------------------------------------------------


@PAGES.screen("feed.html", tab="home")
def feed(request: HttpRequest, page: Page):
    network = page.state
    return {
        "cards": screens.feed(network),
        "news": screens.news(network.catalog),
        "follow": screens.feed_suggestions(network),
        "stats": network.stats,
        "connections_count": connections_count(network),
    }


@PAGES.screen("post.html", tab="home")
def post(request: HttpRequest, page: Page, post_id: str):
    shown(page.state.posts, post_id, "post")
    card = screens.post_card(page.state, post_id)
    return {"cards": (card,), "card": card}


@PAGES.form
def post_action(request: HttpRequest, page: Page, post_id: str, action: str) -> HttpResponse:
    done = act_on_post(request, page, post_id, action, POST_ACTIONS)
    return redirect_after(request, page, came_from(request, page) + f"#post-{post_id}", done)


# --- my network ----------------------------------------------------------------------------------


def network_counts(network: Network) -> dict:
    """What every My Network screen counts. One number of connections everywhere (home, My
    Network, profile): the profile's count, not the length of the list of people we can show."""
    return {"pending": len(screens.invitations(network)), "connections": connections_count(network)}


@PAGES.screen("network.html", tab="network")
def my_network(request: HttpRequest, page: Page):
    preview = screens.invitations(page.state)[: screens.INVITATIONS_PREVIEW]
    suggestions = screens.suggestions(page.state)
    return {"invitations": preview, "suggestions": suggestions, **network_counts(page.state)}


@PAGES.screen("invitations.html", tab="network")
def invitations(request: HttpRequest, page: Page):
    return {"invitations": screens.invitations(page.state), **network_counts(page.state)}


@PAGES.screen("connections.html", tab="network")
def connections(request: HttpRequest, page: Page):
    return {"people": screens.connected_people(page.state), **network_counts(page.state)}


@PAGES.form
def answer_invitation(request: HttpRequest, page: Page, verb: str) -> HttpResponse:
    one_of(verb, INVITATION_VERBS, "answer")
    connection_id = request.POST.get("connection_id", "")
    page.act(INVITATION_VERBS[verb], {"connection_id": connection_id})
    done = ANSWERED[verb].format(page.state.connections[connection_id].person.name)
    return redirect_after(request, page, back_field(request, "mynetwork/"), done)


# --- jobs -------------------------------------------------------------------------------------------


@PAGES.screen("jobs.html", tab="jobs")
def jobs(request: HttpRequest, page: Page):
    query = JobsQuery.from_params(request.GET)
    shown(page.state.jobs, query.job, "job")
    screen = screens.jobs_screen(page.state, query)
    return {"screen": screen, "query": query, "list_query": ending(query, "job")}


@PAGES.form
def apply(request: HttpRequest, page: Page, job_id: str) -> HttpResponse:
    page.act("apply_job", {"job_id": job_id})
    job = page.state.jobs[job_id]
    back = back_field(request, job_path(job_id))
    return redirect_after(request, page, back, f"Application sent to {job.company.name}")


# --- messaging ---------------------------------------------------------------------------------------


@PAGES.screen("messaging.html", tab="messaging")
def messaging(request: HttpRequest, page: Page):
    query = MessagingQuery.from_params(request.GET)
    shown(page.state.conversations, query.conversation, "conversation")
    screen = screens.messaging_screen(page.state, query)
    return {"screen": screen, "query": query, "list_query": ending(query, "conversation")}


send_message = feed_views.send_message("content", thread_path)


@PAGES.form
def start_conversation(request: HttpRequest, page: Page) -> HttpResponse:
    return open_thread(page, request.POST.get("user_id", ""), thread_path, "messaging/")


# --- notifications ------------------------------------------------------------------------------------


@PAGES.screen("notifications.html", tab="notifications")
def notifications(request: HttpRequest, page: Page):
    query = NotificationsQuery.from_params(request.GET)
    rows = screens.notifications_screen(page.state, query)
    return {"rows": rows, "query": query, "filters": NOTIFICATION_FILTER_LABELS}


@PAGES.form
def read_notification(request: HttpRequest, page: Page) -> HttpResponse:
    """Clicking a notification marks it read and goes to what it is about."""
    notification_id = request.POST.get("notification_id", "")
    page.act("mark_notification_read", {"notification_id": notification_id})
    notification = page.state.notifications[notification_id]
    return redirect_to(page, screens.notification_target(page.state, notification))


# --- profile, company, search ---------------------------------------------------------------------------


@PAGES.screen("profile.html")
def profile(request: HttpRequest, page: Page, user_id: str):
    found = present(screens.profile(page.state, user_id), "member")
    tab = "me" if found.is_self else ""
    return {"tab": tab, "profile": found, "section_types": SECTION_TYPES}


@PAGES.form
def add_section(request: HttpRequest, page: Page, user_id: str) -> HttpResponse:
    if user_id != page.state.me.id:
        raise ActionRejected("only your own profile can be edited", 403)
    payload = {k: request.POST.get(k, "") for k in ("type", "title", "subtitle", "content")}
    page.act("add_profile_section", payload)
    return redirect_after(request, page, f"in/{user_id}/", "Section added to your profile")


@PAGES.screen("company.html")
def company(request: HttpRequest, page: Page, company_id: str):
    return {"company_page": present(screens.company_page(page.state, company_id), "company")}


@PAGES.screen("search.html")
def search(request: HttpRequest, page: Page):
    query = SearchQuery.from_params(request.GET)
    return {
        "results": screens.search(page.state, query),
        "query": query,
        "kinds": SEARCH_KIND_LABELS,
    }
