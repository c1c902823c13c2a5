"""What an agent can do to the mailbox: `Action(schema, decide, reduce)` per action name.

`decide(mail, payload)` checks the request against the current mailbox and returns the
payload to log (adding what it decided: a generated id, whether a delete purges). `reduce`
applies a logged action; it trusts the log and never raises, so replay always succeeds (an id
purged meanwhile simply changes nothing).

Flags are set explicitly (flag / unflag), not toggled as upstream did: an agent that repeats a
request, or two tabs that race, cannot flip the flag back by accident.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from types import MappingProxyType
from typing import Literal
from urllib.parse import urlencode

from pydantic import Field

from apps.kit.deciding import checking, found, marking, new_id
from apps.kit.fields import ItemId, ItemIds, Line, Lines, Text
from apps.kit.state import with_changed, with_items, without
from apps.kit.streaming import id_payload
from apps.micromail.query import MailboxQuery
from apps.micromail.state import (
    FOLDERS,
    Attachment,
    Email,
    EmailState,
    Mail,
    attachment_shelf,
    with_favorite,
)
from events.registry import Action, ActionRejected, LoggedEvent, PageStep
from events.schemas import Payload

# Deliberately simple (what a client checks before sending), not RFC 5322.
ADDRESS = re.compile(r"[^@\s,;<>]+@[^@\s,;<>]+\.[^@\s,;<>]+")
PURGED_FROM = ("deleted", "drafts")  # deleting from these folders is permanent


EmailId = id_payload("EmailId", "email_id", "id of a message in the mailbox")


class Move(EmailId):
    # Literal of a tuple means one of its items: state.FOLDERS stays the one list of folders.
    folder: Literal[FOLDERS]


IN_MAILBOX = ("email", "in this mailbox")


def existing_email(mail: Mail, email_id: str) -> Email:
    """The message, or a 404: unknown, purged and not-yet-arrived ids look the same."""
    return found(mail.emails, email_id, *IN_MAILBOX)


decide_on_email = checking("emails", "email_id", *IN_MAILBOX)


def reduce_move(mail: Mail, event: LoggedEvent) -> Mail:
    return with_changed(mail, "states", event.payload["email_id"], folder=event.payload["folder"])


def decide_delete(mail: Mail, payload: dict) -> dict:
    existing_email(mail, payload["email_id"])
    permanent = mail.folder_of(payload["email_id"]) in PURGED_FROM
    return {**payload, "permanent": permanent}


def reduce_delete(mail: Mail, event: LoggedEvent) -> Mail:
    """Move to Deleted Items; from Deleted Items or Drafts, purge the message for good."""
    email_id = event.payload["email_id"]
    if event.payload.get("permanent"):
        return without(mail, email_id, "emails", "states")
    return with_changed(mail, "states", email_id, folder="deleted")


# --- composing ------------------------------------------------------------------------------------


class Compose(Payload):
    """A message to send or a draft to save; null is the same as leaving a field out."""

    to: Lines | None = Field(None, description="addresses")
    cc: Lines | None = Field(None, description="addresses")
    bcc: Lines | None = Field(None, description="addresses")
    subject: Line | None = None
    body: Text | None = None
    attachments: ItemIds | None = Field(
        None, description="ids of documents attached to mail in the mailbox"
    )
    draft_id: ItemId | None = Field(None, description="the draft this replaces")


def address_list(payload: dict, name: str, *, check: bool) -> list[str]:
    addresses = [v.strip() for v in payload.get(name) or () if v.strip()]
    if check:
        for address in addresses:
            if not ADDRESS.fullmatch(address):
                raise ActionRejected(f"'{address}' in {name} is not a valid email address")
    return addresses


def draft_to_replace(mail: Mail, payload: dict) -> dict:
    draft_id = payload.get("draft_id")
    if draft_id is None:
        return {}
    existing_email(mail, draft_id)
    if mail.folder_of(draft_id) != "drafts":
        raise ActionRejected(
            f"email {draft_id!r} is not a draft (it is in {mail.folder_of(draft_id)})"
        )
    return {"draft_id": draft_id}


def attached(mail: Mail, payload: dict) -> list[str]:
    """The attachment ids, each once; every one must be a document of mail in the mailbox."""
    ids = list(dict.fromkeys(payload.get("attachments") or ()))
    available = {a.id for a in attachment_shelf(mail)}
    for attachment_id in ids:
        if attachment_id not in available:
            raise ActionRejected(
                f"no document {attachment_id!r} in this mailbox to put in attachments", status=404
            )
    return ids


def composed(mail: Mail, payload: dict, *, check_addresses: bool) -> dict:
    return {
        **{
            name: address_list(payload, name, check=check_addresses) for name in ("to", "cc", "bcc")
        },
        "subject": payload.get("subject") or "",
        "body": payload.get("body") or "",
        "attachments": attached(mail, payload),
    }


def decide_send(mail: Mail, payload: dict) -> dict:
    message = composed(mail, payload, check_addresses=True)
    if not message["to"]:
        raise ActionRejected("payload field 'to' needs at least one recipient")
    # `<folder>-<hex>`: upstream's id shape.
    return {"id": new_id("sent"), **message, **draft_to_replace(mail, payload)}


def decide_save_draft(mail: Mail, payload: dict) -> dict:
    # Drafts are work in progress: addresses are checked when the draft is sent.
    message = composed(mail, payload, check_addresses=False)
    if not any(message.values()):
        raise ActionRejected(
            "an empty draft has nothing to save: give to, cc, bcc, subject, body or attachments"
        )
    replaced = draft_to_replace(mail, payload)
    return {"id": replaced.get("draft_id") or new_id("drafts"), **message, **replaced}


def documents(mail: Mail, ids: list[str]) -> tuple[Attachment, ...]:
    """The attachments logged by id, as the mailbox holds them at this point of the log (the
    same point on every replay; an id gone meanwhile is skipped, never an error)."""
    shelf = {a.id: a for a in attachment_shelf(mail)}
    return tuple(shelf[i] for i in ids if i in shelf)


def written_by_self(mail: Mail, event: LoggedEvent) -> Email:
    p = event.payload
    attachments = documents(mail, p.get("attachments") or [])
    return Email(
        id=p["id"],
        subject=p["subject"],
        body=p["body"],
        sender_name=mail.self_name,
        sender_email=mail.self_email,
        to=tuple(p["to"]),
        cc=tuple(p["cc"]),
        bcc=tuple(p["bcc"]),  # kept (upstream dropped it): the sender may look it up later
        has_attachment=bool(attachments),
        attachments=attachments,
        arrived_at=event.at,
    )


def filed(mail: Mail, email: Email, folder: str) -> Mail:
    """Mail the self user wrote, in `folder`: read (one's own words), in place of an email with
    the same id (a draft edited again)."""
    mail = with_items(mail, "emails", [(email.id, email)])
    return with_items(mail, "states", [(email.id, EmailState(folder=folder, is_read=True))])


def reduce_send(mail: Mail, event: LoggedEvent) -> Mail:
    """The message lands in Sent Items; a draft it was written from is removed."""
    sent = written_by_self(mail, event)  # before the draft goes: its attachments come along
    draft_id = event.payload.get("draft_id")
    if draft_id:
        mail = without(mail, draft_id, "emails", "states")
    return filed(mail, sent, "sent")


def reduce_save_draft(mail: Mail, event: LoggedEvent) -> Mail:
    """Create a draft, or replace the content of the draft it edits (same id)."""
    return filed(mail, written_by_self(mail, event), "drafts")


# --- favorites ------------------------------------------------------------------------------------


class Favorite(Payload):
    folder: Literal[FOLDERS]


def favoring(on: bool, help: str) -> Action:
    """Add the folder to Favorites (at the end) or take it out; set, not toggled. Any folder
    may be a favourite: the schema has checked it, so the payload is logged as sent."""

    def reduce(mail: Mail, event: LoggedEvent) -> Mail:
        return with_favorite(mail, event.payload["folder"], on=on)

    return Action(Favorite, lambda mail, payload: payload, reduce, help=help, page=favorites_page)


# --- where a person does it in the client (Action.page) ------------------------------------------
# Forms and buttons are marked `data-action="<action>"` in the templates; the generic tests carry
# out every scenario's solution through them (tests/environments/).


def message_screen(mail: Mail, email_id: str) -> str:
    """The mailbox with the message open, in its own folder: `?folder=<folder>&email=<id>`."""
    existing_email(mail, email_id)
    return MailboxQuery(folder=mail.folder_of(email_id)).opening(email_id)


def reading_pane(*fields: str, form: bool = True) -> Callable[[Mail, dict], PageStep]:
    """The open message's reading-pane form for the action, with `fields` of the payload; with
    no `form`, opening the message is the action (an implicit action of the mailbox page)."""

    def page(mail: Mail, payload: dict) -> PageStep:
        values = {name: str(payload[name]) for name in fields}
        return PageStep(message_screen(mail, payload["email_id"]), values if form else None)

    return page


def bulk_mark_read_page(mail: Mail, payload: dict) -> PageStep:
    """The message list's "Mark read" with the message's row checked. Not the reading pane:
    opening a message there already marks it read, so the pane never offers "Mark read"."""
    email_id = payload["email_id"]
    existing_email(mail, email_id)
    return PageStep(
        MailboxQuery(folder=mail.folder_of(email_id)).querystring(), {"ids": [email_id]}
    )


def compose_page(mail: Mail, payload: dict) -> PageStep:
    """The compose form (a new message, or the draft it replaces) with the fields typed in."""
    draft_id = payload.get("draft_id")
    mode = {"mode": "draft", "email": draft_id} if draft_id else {"mode": "new"}
    form = {name: ", ".join(payload.get(name) or ()) for name in ("to", "cc", "bcc")}
    form.update(subject=payload.get("subject") or "", body=payload.get("body") or "")
    if payload.get("attachments"):
        form["attachments"] = list(payload["attachments"])
    return PageStep(f"compose?{urlencode(mode)}", form)


def favorites_page(mail: Mail, payload: dict) -> PageStep:
    """The star next to the folder in the folder pane (any mailbox screen has it)."""
    return PageStep(MailboxQuery().querystring(), {"folder": payload["folder"]})


pane_button = reading_pane()  # the action's button in the open message's reading pane
open_page = reading_pane(form=False)


# An action that sets flags of one message (read, flagged, pinned): set, not toggled.
marks = marking(EmailId, decide_on_email, "states", "email_id", page=pane_button)


ACTIONS: Mapping[str, Action] = MappingProxyType(
    {
        "open_email": marks(
            is_read=True,
            help="Open a message; like any mail client this marks it read.",
            page=open_page,
        ),
        "mark_read": marks(is_read=True, page=bulk_mark_read_page),
        "mark_unread": marks(is_read=False),
        "flag": marks(is_flagged=True),
        "unflag": marks(is_flagged=False),
        "pin": marks(is_pinned=True),
        "unpin": marks(is_pinned=False),
        "move": Action(Move, decide_on_email, reduce_move, page=reading_pane("folder")),
        "delete": Action(
            EmailId,
            decide_delete,
            reduce_delete,
            help="Move to Deleted Items; from Deleted Items or Drafts, delete permanently.",
            page=pane_button,
        ),
        "send": Action(
            Compose,
            decide_send,
            reduce_send,
            help="Send a message from the self user (to is required; bcc is kept).",
            page=compose_page,
        ),
        "save_draft": Action(
            Compose,
            decide_save_draft,
            reduce_save_draft,
            help="Save a draft, or update the draft given by draft_id (the compose form also "
            "saves on its own while one types).",
            page=compose_page,
        ),
        "add_favorite": favoring(True, "Add a folder to Favorites, at the top of the folder pane."),
        "remove_favorite": favoring(False, "Take a folder out of Favorites."),
    }
)
