"""The views of the social feeds (MicroDin, MicroGram): every screen shows the self user, the tab
it belongs to and the navigation's badges; a screen view only says what its screen shows.

    PAGES = FeedPages(badges=screens.badges)

    @PAGES.screen("activity.html", tab="activity")
    def activity(request, page):
        return {"rows": screens.activity(page.state)}

    @PAGES.form
    def read_all_activity(request, page): …   # a form posts here: act, then redirect

The buttons under a post: `act_on_post`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import wraps
from typing import Any

from django.http import Http404, HttpRequest, HttpResponse

from apps.kit.item_actions import act_on_item
from apps.kit.pages import Page, form_view, screen_view
from apps.kit.rendering import redirect_to, render_screen

Context = Mapping[str, Any]
View = Callable[..., HttpResponse]


@dataclass(frozen=True)
class FeedPages:
    badges: Callable[[Any], Any]  # state → the navigation's counts (unread, pending…)

    def show(
        self, request: HttpRequest, page: Page, template: str, tab: str, **context: Any
    ) -> HttpResponse:
        """`<env>/<template>` with the self user `me`, the `tab` and the `badges`."""
        base = {"me": page.state.me, "tab": tab, "badges": self.badges(page.state)}
        template = f"{page.run.environment}/{template}"
        return render_screen(request, page, template, {**base, **context})

    def screen(self, template: str, tab: str = "") -> Callable[[Callable[..., Context]], View]:
        """Decorator: a page of the run that returns its screen's context; a context may name
        its own `tab` (a profile is the "me" tab only when it is the self user's)."""

        def decorate(view: Callable[..., Context]) -> View:
            @wraps(view)
            def render(request: HttpRequest, page: Page, *args: Any, **kwargs: Any):
                context = dict(view(request, page, *args, **kwargs))
                return self.show(request, page, template, context.pop("tab", tab), **context)

            return screen_view(render)

        return decorate

    form = staticmethod(form_view)  # where a form posts: it acts, then redirects


def shown(items: Mapping[str, Any], item_id: str | None, what: str) -> None:
    """A page opening `item_id` (when it names one) is the site's 404 while the run does not
    show it: unknown and not arrived yet look alike."""
    if item_id is not None and item_id not in items:
        raise Http404(f"no such {what}")


def send_message(field: str, thread: Callable[[str], str]) -> View:
    """The view a thread's message form posts to: the message (`field`) is sent, and the
    browser goes back to the thread at `thread(conversation id)`."""

    @FeedPages.form
    def send(request: HttpRequest, page: Page, conversation_id: str) -> HttpResponse:
        text = request.POST.get(field, "")
        page.act("send_message", {"conversation_id": conversation_id, field: text})
        return redirect_to(page, thread(conversation_id))

    return send


def open_thread(page: Page, user_id: str, thread: Callable[[str], str], inbox: str):
    """The thread with that person (a new one if there is none), opened; a read-only (time
    travel) page performs nothing and shows the inbox."""
    event = page.act("start_conversation", {"user_id": user_id})
    if event is None:
        return redirect_to(page, inbox)
    return redirect_to(page, thread(event.payload["conversation_id"]))


# The one post action with a form field: the comment's text.
POST_FORMS = {"comment_post": ("text",)}


def act_on_post(
    request: HttpRequest, page: Page, post_id: str, action: str, notices: Mapping[str, str]
) -> str:
    """A post's button or its comment form (`act_on_item` on the post); returns the toast."""
    return act_on_item(request, page, action, notices, "post_id", post_id, POST_FORMS)
