"""MicroTube pages: thin views over `page.state` (screens.py says what each lists), actions
through `page.act`, post/redirect/get back to the screen the form belongs to.

Every view serves the full page, or only its content when htmx asks for a fragment
(apps.kit.rendering). Opening a watch page is watching the video: declared with the
environment (`implicit_actions`), not done here.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any
from urllib.parse import quote

from django.http import HttpRequest, HttpResponse
from django.views.decorators.http import require_GET

from apps.kit.item_actions import act_on_item
from apps.kit.pages import Page, form_view, one_of, run_page, screen_view
from apps.kit.rendering import redirect_after, redirect_to, render_screen
from apps.kit.streaming import present
from apps.microtube import screens
from apps.microtube.query import ChannelQuery, PlaylistQuery, ResultsQuery, WatchQuery
from apps.microtube.state import SELF_CHANNEL, Tube, Video, unread_notification_count

VIDEO_ACTIONS = {  # action → the toast it shows ("" for none)
    **dict.fromkeys(("like_video", "unlike_video", "dislike_video", "undislike_video"), ""),
    "save_video": "Saved to Watch later",
    "unsave_video": "Removed from Watch later",
    "post_comment": "Comment added",
    "add_to_playlist": "",
}
VIDEO_FORMS = {"post_comment": ("content",), "add_to_playlist": ("playlist_id",)}  # fields posted
CHANNEL_ACTIONS = {"subscribe": "Subscription added", "unsubscribe": "Subscription removed"}
NOTIFICATION_ACTIONS = ("read_notification", "dismiss_notification")


def show(request: HttpRequest, page: Page, template: str, guide: str, **context) -> HttpResponse:
    tube: Tube = page.state
    bell = unread_notification_count(tube)
    base = {
        "me": tube.self_name,
        "self_channel": tube.channels.get(SELF_CHANNEL),
        "guide": guide,
        "bell": bell,
        "bell_label": f"Notifications ({bell} unread)" if bell else "Notifications",
        "notifications": screens.notifications(tube),
        "following": screens.subscribed_channels(tube),
        "search_query": "",
    }
    return render_screen(request, page, f"microtube/{template}", {**base, **context})


def playing(tube: Tube, video: Video) -> dict[str, Any]:
    """What a player (the watch page, a short) shows around the video."""
    return {
        "video": video,
        "channel": tube.channels.get(video.channel_id),
        "rating": tube.video_states[video.id],
        "subscribed": tube.is_subscribed(video.channel_id),
        "comments": screens.comments(tube, video.id),
    }


def watch_path(video_id: str) -> str:
    return "watch" + WatchQuery(v=video_id).querystring()


# --- feeds ----------------------------------------------------------------------------------


def feed(template: str, guide: str, **lists: Callable[[Tube], Any]):
    """A screen that only lists: each of `lists` (a screens function of the state) in its
    context, under the guide entry `guide`."""

    @require_GET
    @run_page
    def view(request: HttpRequest, page: Page) -> HttpResponse:
        shown = {name: screen(page.state) for name, screen in lists.items()}
        return show(request, page, template, guide, **shown)

    return view


home = feed(
    "home.html",
    "home",
    cards=screens.home_videos,
    shelf=screens.home_shorts,
    chips=screens.topics,
)
subscriptions = feed("subscriptions.html", "subscriptions", cards=screens.subscriptions)
history = feed("history.html", "history", cards=screens.history)
you = feed(
    "you.html",
    "you",
    history_cards=lambda tube: screens.history(tube)[:8],
    lists=screens.playlists,
)
playlists = feed("playlists.html", "playlists", lists=screens.playlists)
shorts = feed("shorts.html", "shorts", cards=screens.shorts)
notifications = feed("notifications.html", "notifications")


@screen_view
def playlist(request: HttpRequest, page: Page) -> HttpResponse:
    query = PlaylistQuery.from_params(request.GET)
    shown = present(screens.playlist(page.state, query.list or ""), "playlist")
    return show(request, page, "playlist.html", "playlists", playlist=shown)


@screen_view
def results(request: HttpRequest, page: Page) -> HttpResponse:
    query = ResultsQuery.from_params(request.GET)
    return show(
        request,
        page,
        "results.html",
        "",
        cards=screens.search(page.state, query.search_query),
        search_query=query.search_query,
    )


@screen_view
def short(request: HttpRequest, page: Page, video_id: str) -> HttpResponse:
    """The Shorts player (opening a short is not watching it, as in the original: the history
    keeps what was opened on the watch page)."""
    tube: Tube = page.state
    video = present(tube.videos.get(video_id), "video")
    previous_short, next_short = screens.short_neighbours(tube, video_id)
    return show(
        request,
        page,
        "short.html",
        "shorts",
        **playing(tube, video),
        previous_short=previous_short,
        next_short=next_short,
    )


# --- watch page and what is done there ------------------------------------------------------


@screen_view
def watch(request: HttpRequest, page: Page) -> HttpResponse:
    tube: Tube = page.state
    video_id = WatchQuery.from_params(request.GET).v
    video = present(tube.videos.get(video_id or ""), "video")
    return show(
        request,
        page,
        "watch.html",
        "",
        **playing(tube, video),
        related=screens.related(tube, video.id),
        lists=[p for p in screens.playlists(tube) if not p.built_in],
    )


@form_view
def video_action(request: HttpRequest, page: Page, video_id: str, action: str) -> HttpResponse:
    done = act_on_item(request, page, action, VIDEO_ACTIONS, "video_id", video_id, VIDEO_FORMS)
    if action == "add_to_playlist":
        done = f"Saved to {page.state.playlists[request.POST.get('playlist_id', '')].name}"
    if request.POST.get("back") == "shorts":  # the form was in the Shorts player
        return redirect_after(request, page, f"shorts/{quote(video_id)}", done)
    anchor = "#comments" if action == "post_comment" else ""
    return redirect_after(request, page, watch_path(video_id) + anchor, done)


@form_view
def new_playlist(request: HttpRequest, page: Page) -> HttpResponse:
    video_id = request.POST.get("video_id") or None
    form = {"name": request.POST.get("name", ""), "video_id": video_id}
    done = f"Created playlist {page.act('create_playlist', form).payload['name']}"
    return redirect_after(
        request, page, watch_path(video_id) if video_id else "feed/playlists", done
    )


# --- channels -------------------------------------------------------------------------------


@screen_view
def channel(request: HttpRequest, page: Page, channel_id: str) -> HttpResponse:
    tube: Tube = page.state
    shown = present(tube.channels.get(channel_id), "channel")
    query = ChannelQuery.from_params(request.GET)
    return show(
        request,
        page,
        "channel.html",
        "you" if shown.is_self else "",
        channel=shown,
        tab=query.tab,
        subscribed=tube.is_subscribed(channel_id),
        cards=screens.channel_videos(tube, channel_id),
    )


@form_view
def channel_action(request: HttpRequest, page: Page, channel_id: str, action: str) -> HttpResponse:
    done = act_on_item(request, page, action, CHANNEL_ACTIONS, "channel_id", channel_id)
    # Back to the video the button was under, or to the channel page.
    video_id = request.POST.get("video_id", "")
    back = f"channel/{quote(channel_id)}"
    if video_id in page.state.videos:
        on_shorts = request.POST.get("back") == "shorts"
        back = f"shorts/{quote(video_id)}" if on_shorts else watch_path(video_id)
    return redirect_after(request, page, back, done)


# --- notifications --------------------------------------------------------------------------


@form_view
def notification_action(request: HttpRequest, page: Page, action: str) -> HttpResponse:
    one_of(action, NOTIFICATION_ACTIONS, "notification action")
    notification_id = request.POST.get("notification_id", "")
    page.act(action, {"notification_id": notification_id})
    if action == "read_notification":
        return redirect_to(page, screens.notification_target(page.state, notification_id))
    return redirect_to(page, "notifications")
