"""MicroChat pages: thin views over `page.state`, actions through `page.act`.

Every screen has its own URL (query.py); actions are POST forms that carry the id they act on
and return to the screen they came from (post/redirect/get). Opening a chat marks it read:
declared with the environment (`implicit_actions`), not here.
"""

from __future__ import annotations

from django.http import Http404, HttpRequest, HttpResponse

from apps.kit import simclock
from apps.kit.item_actions import act_on_item
from apps.kit.pages import Page, form_view, one_of, screen_view
from apps.kit.rendering import redirect_after, redirect_to, render_screen
from apps.kit.streaming import present
from apps.microchat import screens
from apps.microchat.actions import existing_conversation, existing_message
from apps.microchat.calendar import calendar_grid
from apps.microchat.query import CalendarQuery, CallsQuery, ChatQuery, SearchQuery

CONVERSATION_ACTIONS = {
    "pin": "Added to Favorites",
    "unpin": "Removed from Favorites",
    "mute": "Chat muted",
    "unmute": "Chat unmuted",
    "mark_unread": "Marked as unread",
}
MESSAGE_ACTIONS = {
    "react": "",
    "unreact": "",
    "edit_message": "Message edited",
    "delete_message": "Message deleted",
}
# What a message action's form posts besides the message's id.
FORMS = {"react": ("reaction",), "unreact": ("reaction",), "edit_message": ("content",)}


def show(page: Page, name: str, *, section: str = "", **context: object) -> HttpResponse:
    """The screen `microchat/<name>.html` with the chrome's context; the app rail marks
    `section` (the screen's own name unless told)."""
    chat = page.state
    first = chat.self_name.split()[0] if chat.self_name.split() else chat.self_name
    chrome = {
        "section": section or name,
        "self_name": chat.self_name,
        "self_names": (chat.self_name, first),
        "rail": screens.rail(chat),
    }
    return render_screen(page.request, page, f"microchat/{name}.html", {**chrome, **context})


@screen_view
def chat(request: HttpRequest, page: Page) -> HttpResponse:
    """The chat list, with `conversation=<id>` open (opening has marked it read)."""
    query = ChatQuery.from_params(request.GET)
    opened = None
    if query.conversation is not None:
        if not page.state.has_conversation(query.conversation):
            raise Http404("no such conversation")
        opened = screens.open_conversation(page.state, query)
    listing = screens.chat_list(page.state, query, page.root + "/")
    back = query.querystring()
    return show(page, "chat", query=query, listing=listing, opened=opened, back=back)


@screen_view
def search(request: HttpRequest, page: Page) -> HttpResponse:
    q = SearchQuery.from_params(request.GET).q
    results = screens.search(page.state, q, page.root + "/")
    return show(page, "search", section="chat", search_q=q, results=results)


@screen_view
def teams(request: HttpRequest, page: Page) -> HttpResponse:
    return show(page, "teams", cards=screens.team_cards(page.state, page.root + "/"))


@screen_view
def team(request: HttpRequest, page: Page, team_id: str, channel_id: str = "") -> HttpResponse:
    found = present(page.state.teams.get(team_id), "team")
    channel_id = channel_id or (found.channels[0].id if found.channels else "")
    channel = next((c for c in found.channels if c.id == channel_id), None)
    if found.channels and channel is None:
        raise Http404("no such channel")
    return show(
        page,
        "team",
        section="teams",
        cards=screens.team_cards(page.state, page.root + "/"),
        detail=screens.team_detail(page.state, found, channel_id),
        channel=channel,
    )


@screen_view
def calendar(request: HttpRequest, page: Page) -> HttpResponse:
    query = CalendarQuery.from_params(request.GET)
    zero = simclock.day_zero(page.run)
    today = simclock.today(page.now, zero)
    found = screens.meetings(page.state, zero, page.root + "/")
    views = [
        (v, v.title(), query.but(view=v, offset="0").querystring())
        for v in ("day", "week", "month")
    ]
    grid = calendar_grid(query, today, found)
    return show(page, "calendar", query=query, grid=grid, views=views)


@screen_view
def calls(request: HttpRequest, page: Page) -> HttpResponse:
    query = CallsQuery.from_params(request.GET)
    calls_screen = screens.calls_screen(page.state, query)
    return show(page, "calls", query=query, screen=calls_screen)


@screen_view
def activity(request: HttpRequest, page: Page) -> HttpResponse:
    items = screens.activity(page.state, page.root + "/")
    return show(page, "activity", items=items)


def back_to(
    page: Page, request: HttpRequest, done: str, *, close: str | None = None
) -> HttpResponse:
    """Back to the screen the form was on, `done` shown once; `close`: leave that chat closed
    (after marking it unread, or the redirect would open it — and read it — again)."""
    back = ChatQuery.from_querystring(request.POST.get("back", ""))
    if back.conversation and (
        back.conversation == close or not page.state.has_conversation(back.conversation)
    ):
        back = back.but(conversation=None, find="", reply="")
    return redirect_after(request, page, back.querystring(), done)


@form_view
def conversation_action(request: HttpRequest, page: Page, action: str) -> HttpResponse:
    """`POST conversations/<action>` with `conversation_id`: pin, unpin, mute, unmute,
    mark_unread."""
    one_of(action, CONVERSATION_ACTIONS, "chat action")
    conversation_id = request.POST.get("conversation_id", "")
    existing_conversation(page.state, conversation_id)
    page.act(action, {"conversation_id": conversation_id})
    closed = conversation_id if action == "mark_unread" else None
    return back_to(page, request, CONVERSATION_ACTIONS[action], close=closed)


@form_view
def message_action(request: HttpRequest, page: Page, action: str) -> HttpResponse:
    """`POST messages/<action>` with `message_id` (react/unreact: `reaction`; edit: `content`)."""
    one_of(action, MESSAGE_ACTIONS, "message action")
    message_id = request.POST.get("message_id", "")
    existing_message(page.state, message_id)
    done = act_on_item(request, page, action, MESSAGE_ACTIONS, "message_id", message_id, FORMS)
    return back_to(page, request, done)


@form_view
def send(request: HttpRequest, page: Page) -> HttpResponse:
    """`POST send` with `conversation_id`, `content` and optional `reply_to`."""
    payload = {field: request.POST.get(field, "") for field in ("conversation_id", "content")}
    if request.POST.get("reply_to"):
        payload["reply_to"] = request.POST["reply_to"]
    page.act("send_message", payload)
    query = ChatQuery.from_querystring(request.POST.get("back", "")).but(reply="")
    return redirect_to(page, query.querystring())
