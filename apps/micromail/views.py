"""MicroMail pages: thin views over `page.state`, actions through `page.act`.

Every view serves the full page, or just the `#mailbox` content when htmx asks for a fragment
(apps.kit.rendering). Actions are POST forms that redirect back to the screen they came
from (post/redirect/get), so the site works with plain links and forms; htmx only makes it
smoother. Opening a message marks it read: declared with the environment (`implicit_actions`).
"""

from __future__ import annotations

from django.contrib import messages
from django.http import Http404, HttpRequest, HttpResponse, JsonResponse
from django.views.decorators.http import require_http_methods

from apps.kit.pages import Page, chosen, form_view, one_of, run_page, screen_view
from apps.kit.rendering import is_fragment, redirect_after, redirect_to, render_screen
from apps.micromail.actions import existing_email
from apps.micromail.compose import COMPOSE_MODES, Composition, prefill
from apps.micromail.query import MailboxQuery
from apps.micromail.screens import (
    attachment_choices,
    attachment_of,
    compose_url,
    favorite_links,
    folder_links,
    mailbox_screen,
)
from apps.micromail.state import FOLDER_TITLES, FOLDERS
from events.registry import ActionRejected

EMAIL_ACTIONS = ("mark_read", "mark_unread", "flag", "unflag", "pin", "unpin", "move", "delete")
# After these the message leaves the screen it was open on (marking unread closes it, or the
# redirect would open it — and mark it read — again).
CLOSES_THE_MESSAGE = ("mark_unread", "move", "delete")
COMPOSE_INTENTS = ("send", "save_draft", "discard", "discard_confirmed", "edit")
DONE = {
    "mark_read": "marked as read",
    "mark_unread": "marked as unread",
    "flag": "flagged",
    "unflag": "unflagged",
    "pin": "pinned",
    "unpin": "unpinned",
    "delete": "deleted",
}


FAVORITE_ACTIONS = {"add_favorite": "added to", "remove_favorite": "removed from"}
# Sent by the compose form's own saving (static/micromail/micromail.js): answered with the draft's id.
AUTOSAVE_HEADER = "X-MicroMail-Autosave"


def base_context(page: Page, current_folder: str | None, back: str = "") -> dict:
    """What the chrome shows on every page; `back` = the screen the folder stars return to."""
    mail, root = page.state, page.root + "/"
    return {
        "token": page.run.token,
        "self_name": mail.self_name,
        "self_first_name": mail.self_name.split()[0] if mail.self_name.split() else mail.self_name,
        "self_email": mail.self_email,
        "folders": folder_links(mail, current_folder, root),
        "favorites": favorite_links(mail, current_folder, root),
        "folders_back": back,
        "compose_url": compose_url(root, "new"),
        "all_folders": [(f, FOLDER_TITLES[f]) for f in FOLDERS],
    }


def render_mailbox(request: HttpRequest, page: Page, query: MailboxQuery) -> HttpResponse:
    screen = mailbox_screen(page.state, query, page.root + "/")
    context = {
        **base_context(page, query.folder, screen.back),
        "screen": screen,
        "query": query,
    }
    return render_screen(request, page, "micromail/mailbox.html", context)


def back_to(request: HttpRequest, page: Page, query: MailboxQuery) -> HttpResponse:
    if query.email and not page.state.has(query.email):
        query = query.but(email=None, preview=None)  # the open message was purged meanwhile
    if is_fragment(request):
        return render_mailbox(request, page, query)
    return redirect_to(page, query.querystring())


@screen_view
def mailbox(request: HttpRequest, page: Page) -> HttpResponse:
    """The mail client, with message `email=<id>` open (which has marked it read)."""
    query = MailboxQuery.from_params(request.GET)
    if query.email is not None and not page.state.has(query.email):
        raise Http404("no such email")  # unknown, purged, or not arrived yet: all alike
    if query.preview is not None and (
        query.email is None or attachment_of(page.state.emails[query.email], query.preview) is None
    ):
        raise Http404("no such attachment on the open email")
    return render_mailbox(request, page, query)


def _payload(action: str, email_id: str, folder: str) -> dict:
    return {"email_id": email_id, "folder": folder} if action == "move" else {"email_id": email_id}


def _confirmation(action: str, folder: str, count: int, permanent: bool = False) -> str:
    what = "1 email" if count == 1 else f"{count} emails"
    if action == "move":
        return f"{what} moved to {FOLDER_TITLES.get(folder, 'a folder')}"
    if action == "delete" and permanent:
        return f"{what} deleted permanently"
    return f"{what} {DONE[action]}"


def _returning(request: HttpRequest, action: str, acted_on: list[str]) -> MailboxQuery:
    back = MailboxQuery.from_querystring(request.POST.get("back", ""))
    if action in CLOSES_THE_MESSAGE and back.email in acted_on:
        back = back.but(email=None, preview=None)
    return back


def pressed(request: HttpRequest) -> tuple[str, str]:
    """The action the pressed button asked for, and the folder of a move. An item of a "Move to"
    menu is a button `move_to=<folder>` (a button carries one value); any other button is
    `action=<name>`, a move taking the form's `folder`."""
    if "move_to" in request.POST:
        return "move", request.POST["move_to"]
    return request.POST.get("action", ""), request.POST.get("folder", "")


def act_on_emails(
    request: HttpRequest, page: Page, action: str, ids: list[str], folder: str
) -> HttpResponse:
    """`action` on each message of `ids` (a move, to `folder`), then back to the screen the
    form was on."""
    permanent = False
    for email_id in ids:
        event = page.act(action, _payload(action, email_id, folder))
        permanent |= event.payload.get("permanent", False)
    messages.success(request, _confirmation(action, folder, len(ids), permanent))
    return back_to(request, page, _returning(request, action, ids))


@form_view
def email_action(request: HttpRequest, page: Page, email_id: str, action: str) -> HttpResponse:
    """`POST emails/<id>/<action>` (move also takes `folder`), then back to the same screen."""
    action = one_of(action, EMAIL_ACTIONS, "email action")
    return act_on_emails(request, page, action, [email_id], request.POST.get("folder", ""))


@form_view
def bulk_action(request: HttpRequest, page: Page) -> HttpResponse:
    """The checked messages (`ids`), one action each; all ids are checked before any acts."""
    chosen, folder = pressed(request)
    action = one_of(chosen, EMAIL_ACTIONS, "email action")
    ids = list(dict.fromkeys(request.POST.getlist("ids")))
    if not ids:
        messages.info(request, "Select at least one email first.")
        return back_to(request, page, _returning(request, action, []))
    for email_id in ids:
        existing_email(page.state, email_id)
    return act_on_emails(request, page, action, ids, folder)


@form_view
def favorite_action(request: HttpRequest, page: Page) -> HttpResponse:
    """`POST favorites` (`action` = add_favorite|remove_favorite, `folder`), then back."""
    action = one_of(request.POST.get("action"), FAVORITE_ACTIONS, "favorites action")
    folder = request.POST.get("folder", "")
    page.act(action, {"folder": folder})
    messages.success(request, f"{FOLDER_TITLES[folder]} {FAVORITE_ACTIONS[action]} Favorites")
    return back_to(request, page, MailboxQuery.from_querystring(request.POST.get("back", "")))


def render_compose(
    request: HttpRequest, page: Page, composition: Composition, *, error: str = "", status=200
) -> HttpResponse:
    chosen = set(composition.attachments)
    context = {
        **base_context(page, None),
        **composition.address_fields(),
        "composition": composition,
        "attachment_choices": [(a, a.id in chosen) for a in attachment_choices(page.state)],
        "error": error,
    }
    return render_screen(request, page, "micromail/compose.html", context, status=status)


@require_http_methods(["GET", "POST"])
@run_page
def compose(request: HttpRequest, page: Page) -> HttpResponse:
    """GET: the compose form (`mode` = new|reply|reply_all|forward|draft, `email` = about which).

    POST: `intent` = send|save_draft with to/cc/bcc (comma or semicolon separated), subject,
    body, attachments (ids, repeated) and optional draft_id. A rejected message comes back with
    the typed text kept. `intent=discard` asks for confirmation (a page holding what was typed);
    from there `discard_confirmed` deletes the auto-saved draft, `edit` returns to the form.
    The compose form's own saving sends save_draft with the AUTOSAVE_HEADER: answered in JSON.
    """
    if request.method == "GET":
        mode = chosen("mode", request.GET.get("mode") or "new", COMPOSE_MODES)
        return render_compose(request, page, prefill(page.state, mode, request.GET.get("email")))
    intent = chosen("intent", request.POST.get("intent", "send"), COMPOSE_INTENTS)
    typed = Composition.typed(request.POST)
    if intent == "edit":  # back from the discard confirmation: the form as it was
        return render_compose(request, page, typed)
    if intent == "discard":
        context = {**base_context(page, None), **typed.address_fields(), "typed": typed}
        return render_screen(request, page, "micromail/discard.html", context)
    if intent == "discard_confirmed":
        return discard(request, page, typed)
    try:
        event = page.act(intent, typed.payload())
    except ActionRejected as exc:
        if request.headers.get(AUTOSAVE_HEADER):
            return JsonResponse({"error": str(exc)}, status=exc.status)
        return render_compose(request, page, typed, error=str(exc), status=exc.status)
    if request.headers.get(AUTOSAVE_HEADER):
        return JsonResponse({"draft_id": event.payload["id"]})
    if intent == "send":
        sent = MailboxQuery(folder="sent", email=event.payload["id"])
        return redirect_after(request, page, sent.querystring(), "Message sent")
    return redirect_after(request, page, MailboxQuery(folder="drafts").querystring(), "Draft saved")


def discard(request: HttpRequest, page: Page, typed: Composition) -> HttpResponse:
    """Confirmed: the auto-saved draft is deleted for good (a draft deleted from Drafts is
    purged), and the user is back in the inbox."""
    draft_id, done = typed.draft_id, "Message discarded"
    if draft_id and page.state.has(draft_id) and page.state.folder_of(draft_id) == "drafts":
        page.act("delete", {"email_id": draft_id})
        done = "Draft discarded"
    return redirect_after(request, page, MailboxQuery(folder="inbox").querystring(), done)
