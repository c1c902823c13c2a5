"""MicroGram pages: thin views over `page.state` (screens.py says what each shows), actions
through `page.act`, post/redirect/get back to the screen the form was on.

Opening a post, a story or a DM thread views / reads it: declared with the environment
(`implicit_actions`), not done here.
"""

from __future__ import annotations

from django.http import Http404, HttpRequest, HttpResponse
from django.views.decorators.http import require_GET, require_POST

from apps.kit.feeds import thread_with
from apps.kit.pages import Page, one_of, run_page
from apps.kit.post_actions import act_on_post
from apps.kit.rendering import (
    came_from,
    redirect_after,
    redirect_to,
    render_screen,
)
from apps.microgram import screens
from apps.microgram.catalog import person
from apps.microgram.query import ExploreQuery, FeedQuery, ProfileQuery, SearchQuery
from apps.microgram.state import Gram, comments_of, is_following, known_people

POST_ACTIONS = {
    "like_post": "",
    "unlike_post": "",
    "save_post": "Saved",
    "unsave_post": "Removed from saved",
    "comment_post": "Comment posted",
}
FOLLOW_VERBS = {"follow": "follow_user", "unfollow": "unfollow_user"}


def show(request: HttpRequest, page: Page, template: str, tab: str, **context) -> HttpResponse:
    gram: Gram = page.state
    base = {"me": gram.me, "tab": tab, "badges": screens.badges(gram)}
    return render_screen(request, page, f"microgram/{template}", {**base, **context})


# --- home feed, posts, stories ------------------------------------------------------------------


@require_GET
@run_page
def feed(request: HttpRequest, page: Page) -> HttpResponse:
    gram = page.state
    query = FeedQuery.from_params(request.GET)
    cards = screens.feed(gram)
    more = query.but(page=str(int(query.page) + 1)) if len(cards) > query.shown else None
    return show(
        request,
        page,
        "feed.html",
        "home",
        query=query,
        cards=cards[: query.shown],
        total=len(cards),
        more=more,
        bubbles=screens.story_bar(gram),
        suggestions=screens.suggestions(gram),
    )


@require_GET
@run_page
def post(request: HttpRequest, page: Page, post_id: str) -> HttpResponse:
    gram = page.state
    if post_id not in gram.posts:
        raise Http404("no such post")  # unknown or not posted yet: alike
    return show(
        request,
        page,
        "post.html",
        "home",
        card=screens.card(gram, post_id),
        comments=comments_of(gram, post_id),
        threads=screens.inbox(gram),
        followed=is_following(gram, gram.posts[post_id].author.id),
    )


@require_POST
@run_page
def post_action(request: HttpRequest, page: Page, post_id: str, action: str) -> HttpResponse:
    done = act_on_post(request, page, post_id, action, POST_ACTIONS)
    back = came_from(request, page, f"p/{post_id}/")
    if not back.startswith("p/"):
        back += f"#post-{post_id}"  # back to the post in a list, not to the list's top
    return redirect_after(request, page, back, done)


@require_POST
@run_page
def share(request: HttpRequest, page: Page, post_id: str) -> HttpResponse:
    conversation_id = request.POST.get("conversation_id", "")
    page.act(
        "share_post",
        {
            "post_id": post_id,
            "conversation_id": conversation_id,
            "text": request.POST.get("text", ""),
        },
    )
    return redirect_after(request, page, f"p/{post_id}/", "Sent")


@require_GET
@run_page
def story(request: HttpRequest, page: Page, story_id: str) -> HttpResponse:
    gram = page.state
    if story_id not in gram.stories:
        raise Http404("no such story")
    previous, following = screens.story_neighbours(gram, story_id)
    return show(
        request,
        page,
        "story.html",
        "home",
        story=gram.stories[story_id],
        previous=previous,
        next=following,
        bubbles=screens.story_bar(gram),
    )


# --- explore and search --------------------------------------------------------------------------


@require_GET
@run_page
def explore(request: HttpRequest, page: Page) -> HttpResponse:
    query = ExploreQuery.from_params(request.GET)
    return show(
        request,
        page,
        "explore.html",
        "explore",
        query=query,
        cards=screens.explore(page.state, query.q),
    )


@require_GET
@run_page
def search(request: HttpRequest, page: Page) -> HttpResponse:
    query = SearchQuery.from_params(request.GET)
    gram = page.state
    return show(
        request,
        page,
        "search.html",
        "search",
        query=query,
        people=screens.search_people(gram, query.q),
        suggestions=screens.suggestions(gram),
    )


# --- direct messages -----------------------------------------------------------------------------


@require_GET
@run_page
def inbox(request: HttpRequest, page: Page) -> HttpResponse:
    return show(request, page, "direct.html", "direct", rows=screens.inbox(page.state), open=None)


@require_GET
@run_page
def thread(request: HttpRequest, page: Page, conversation_id: str) -> HttpResponse:
    gram = page.state
    if conversation_id not in gram.conversations:
        raise Http404("no such conversation")
    return show(
        request,
        page,
        "direct.html",
        "direct",
        rows=screens.inbox(gram),
        open=gram.conversations[conversation_id],
        thread_messages=screens.thread(gram, conversation_id),
    )


@require_POST
@run_page
def send_message(request: HttpRequest, page: Page, conversation_id: str) -> HttpResponse:
    page.act(
        "send_message", {"conversation_id": conversation_id, "text": request.POST.get("text", "")}
    )
    return redirect_to(page, f"direct/t/{conversation_id}/")


# --- activity ------------------------------------------------------------------------------------


@require_GET
@run_page
def activity(request: HttpRequest, page: Page) -> HttpResponse:
    return show(request, page, "activity.html", "activity", rows=screens.activity(page.state))


@require_POST
@run_page
def read_activity(request: HttpRequest, page: Page) -> HttpResponse:
    """Reading one item (clicking it) goes on to what it is about: the post, else the person."""
    activity_id = request.POST.get("activity_id", "")
    page.act("mark_activity_read", {"activity_id": activity_id})
    item = page.state.activity[activity_id]
    if item.target_post_id in page.state.posts:
        return redirect_to(page, f"p/{item.target_post_id}/")
    return redirect_to(page, f"profile/{item.actor.id}/")


@require_POST
@run_page
def read_all_activity(request: HttpRequest, page: Page) -> HttpResponse:
    page.act("mark_all_activity_read", {})
    return redirect_after(request, page, "activity/", "All activity marked as read")


# --- profiles ------------------------------------------------------------------------------------


def member(page: Page, user_id: str):
    if user_id not in known_people(page.state):
        raise Http404("no such member")  # unknown or not seen on MicroGram yet: alike
    return person(page.state.catalog, user_id)


@require_GET
@run_page
def profile(request: HttpRequest, page: Page, user_id: str) -> HttpResponse:
    member(page, user_id)
    query = ProfileQuery.from_params(request.GET)
    view = screens.profile(page.state, user_id, query.tab)
    tab = "profile" if view.is_self else ""
    thread = thread_with(page.state, user_id)
    return show(request, page, "profile.html", tab, query=query, view=view, thread=thread)


@require_GET
@run_page
def following(request: HttpRequest, page: Page, user_id: str) -> HttpResponse:
    if user_id != page.state.me.id:
        raise Http404("only your own following list is shown")
    return show(request, page, "following.html", "profile", people=screens.following(page.state))


@require_POST
@run_page
def message(request: HttpRequest, page: Page, user_id: str) -> HttpResponse:
    """The Message button: the thread with that person (a new one if there is none)."""
    event = page.act("start_conversation", {"user_id": user_id})
    if event is None:  # a read-only (time travel) page performs nothing
        return redirect_to(page, "direct/inbox/")
    return redirect_to(page, f"direct/t/{event.payload['conversation_id']}/")


@require_POST
@run_page
def follow(request: HttpRequest, page: Page, user_id: str, verb: str) -> HttpResponse:
    one_of(verb, FOLLOW_VERBS, "verb")
    page.act(FOLLOW_VERBS[verb], {"user_id": user_id})
    return redirect_to(page, came_from(request, page, f"profile/{user_id}/"))
