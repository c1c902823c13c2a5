"""MicroGram pages: thin views over `page.state` (screens.py says what each shows), actions
through `page.act`, post/redirect/get back to the screen the form was on.

Opening a post, a story or a DM thread views / reads it: declared with the environment
(`implicit_actions`), not done here.
"""

from __future__ import annotations

from django.http import Http404, HttpRequest, HttpResponse

from apps.kit import feed_views
from apps.kit.feed_views import FeedPages, act_on_post, open_thread, shown
from apps.kit.feeds import thread_with
from apps.kit.pages import Page, one_of
from apps.kit.rendering import came_from, redirect_after, redirect_to
from apps.microgram import screens
from apps.microgram.query import FeedQuery, ProfileQuery, SearchQuery
from apps.microgram.state import comments_of, is_following, known_people

PAGES = FeedPages(badges=screens.badges)
POST_ACTIONS = {
    "like_post": "",
    "unlike_post": "",
    "save_post": "Saved",
    "unsave_post": "Removed from saved",
    "comment_post": "Comment posted",
}
FOLLOW_VERBS = {"follow": "follow_user", "unfollow": "unfollow_user"}


def thread_path(conversation_id: str) -> str:
    return f"direct/t/{conversation_id}/"


# --- home feed, posts, stories ------------------------------------------------------------------


@PAGES.screen("feed.html", tab="home")
def feed(request: HttpRequest, page: Page):
    gram = page.state
    query = FeedQuery.from_params(request.GET)
    cards = screens.feed(gram)
    more = query.but(page=str(int(query.page) + 1)) if len(cards) > query.shown else None
    return {
        "query": query,
        "cards": cards[: query.shown],
        "total": len(cards),
        "more": more,
        "bubbles": screens.story_bar(gram),
        "suggestions": screens.suggestions(gram),
    }


@PAGES.screen("post.html", tab="home")
def post(request: HttpRequest, page: Page, post_id: str):
    gram = page.state
    shown(gram.posts, post_id, "post")
    return {
        "card": screens.card(gram, post_id),
        "comments": comments_of(gram, post_id),
        "threads": screens.inbox(gram),
        "followed": is_following(gram, gram.posts[post_id].author.id),
    }


@PAGES.form
def post_action(request: HttpRequest, page: Page, post_id: str, action: str) -> HttpResponse:
    done = act_on_post(request, page, post_id, action, POST_ACTIONS)
    back = came_from(request, page, f"p/{post_id}/")
    if not back.startswith("p/"):
        back += f"#post-{post_id}"  # back to the post in a list, not to the list's top
    return redirect_after(request, page, back, done)


@PAGES.form
def share(request: HttpRequest, page: Page, post_id: str) -> HttpResponse:
    form = {field: request.POST.get(field, "") for field in ("conversation_id", "text")}
    page.act("share_post", {"post_id": post_id, **form})
    return redirect_after(request, page, f"p/{post_id}/", "Sent")


@PAGES.screen("story.html", tab="home")
def story(request: HttpRequest, page: Page, story_id: str):
    gram = page.state
    shown(gram.stories, story_id, "story")
    previous, following = screens.story_neighbours(gram, story_id)
    return {
        "story": gram.stories[story_id],
        "previous": previous,
        "next": following,
        "bubbles": screens.story_bar(gram),
    }


# --- explore and search --------------------------------------------------------------------------


@PAGES.screen("explore.html", tab="explore")
def explore(request: HttpRequest, page: Page):
    query = SearchQuery.from_params(request.GET)
    return {"query": query, "cards": screens.explore(page.state, query.q)}


@PAGES.screen("search.html", tab="search")
def search(request: HttpRequest, page: Page):
    query = SearchQuery.from_params(request.GET)
    people = screens.search_people(page.state, query.q)
    return {"query": query, "people": people, "suggestions": screens.suggestions(page.state)}


# --- direct messages -----------------------------------------------------------------------------


@PAGES.screen("direct.html", tab="direct")
def inbox(request: HttpRequest, page: Page):
    return {"rows": screens.inbox(page.state), "open": None}


@PAGES.screen("direct.html", tab="direct")
def thread(request: HttpRequest, page: Page, conversation_id: str):
    gram = page.state
    shown(gram.conversations, conversation_id, "conversation")
    return {
        "rows": screens.inbox(gram),
        "open": gram.conversations[conversation_id],
        "thread_messages": screens.thread(gram, conversation_id),
    }


send_message = feed_views.send_message("text", thread_path)


# --- activity ------------------------------------------------------------------------------------


@PAGES.screen("activity.html", tab="activity")
def activity(request: HttpRequest, page: Page):
    return {"rows": screens.activity(page.state)}


@PAGES.form
def read_activity(request: HttpRequest, page: Page) -> HttpResponse:
    """Reading one item (clicking it) goes on to what it is about: the post, else the person."""
    activity_id = request.POST.get("activity_id", "")
    page.act("mark_activity_read", {"activity_id": activity_id})
    item = page.state.activity[activity_id]
    if item.target_post_id in page.state.posts:
        return redirect_to(page, f"p/{item.target_post_id}/")
    return redirect_to(page, f"profile/{item.actor.id}/")


@PAGES.form
def read_all_activity(request: HttpRequest, page: Page) -> HttpResponse:
    page.act("mark_all_activity_read", {})
    return redirect_after(request, page, "activity/", "All activity marked as read")


# --- profiles ------------------------------------------------------------------------------------


@PAGES.screen("profile.html")
def profile(request: HttpRequest, page: Page, user_id: str):
    shown(known_people(page.state), user_id, "member")  # unknown or not seen yet: alike
    query = ProfileQuery.from_params(request.GET)
    view = screens.profile(page.state, user_id, query.tab)
    return {
        "tab": "profile" if view.is_self else "",
        "query": query,
        "view": view,
        "thread": thread_with(page.state, user_id),
    }


@PAGES.screen("following.html", tab="profile")
def following(request: HttpRequest, page: Page, user_id: str):
    if user_id != page.state.me.id:
        raise Http404("only your own following list is shown")
    return {"people": screens.following(page.state)}


@PAGES.form
def message(request: HttpRequest, page: Page, user_id: str) -> HttpResponse:
    """The Message button: the thread with that person (a new one if there is none)."""
    return open_thread(page, user_id, thread_path, "direct/inbox/")


@PAGES.form
def follow(request: HttpRequest, page: Page, user_id: str, verb: str) -> HttpResponse:
    one_of(verb, FOLLOW_VERBS, "verb")
    page.act(FOLLOW_VERBS[verb], {"user_id": user_id})
    return redirect_to(page, came_from(request, page, f"profile/{user_id}/"))
