"""Prefilled compose forms (new, reply, reply all, forward, edit draft): pure functions of state.

Nothing here changes the mailbox; a composition becomes mail only through the `send` or
`save_draft` action.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from apps.kit.simclock import clock_time
from apps.micromail.actions import existing_email
from apps.micromail.state import Email, Mail
from events.registry import ActionRejected

COMPOSE_MODES: tuple[str, ...] = ("new", "reply", "reply_all", "forward", "draft")
ADDRESS_FIELDS = ("to", "cc", "bcc")
_SEPARATORS = re.compile(r"[,;]")


@dataclass(frozen=True)
class Composition:
    mode: str = "new"
    to: tuple[str, ...] = ()
    cc: tuple[str, ...] = ()
    bcc: tuple[str, ...] = ()
    subject: str = ""
    body: str = ""
    attachments: tuple[str, ...] = ()  # ids of documents in the mailbox (attachment_shelf)
    draft_id: str | None = None  # set when editing a draft: sending or saving replaces it

    @classmethod
    def typed(cls, form: Any) -> Composition:
        """What was typed in the compose form (its POST data), to act on or to show again."""
        draft_id = form.get("draft_id") or None
        return cls(
            "draft" if draft_id else "new",
            *(tuple(split_addresses(form.get(field, ""))) for field in ADDRESS_FIELDS),
            subject=form.get("subject", ""),
            body=form.get("body", ""),
            attachments=tuple(form.getlist("attachments")),
            draft_id=draft_id,
        )

    def payload(self) -> dict:
        """The `send` or `save_draft` payload of this composition."""
        payload = {field: list(getattr(self, field)) for field in ADDRESS_FIELDS}
        payload.update(subject=self.subject, body=self.body, attachments=list(self.attachments))
        return {**payload, "draft_id": self.draft_id} if self.draft_id else payload

    def address_fields(self) -> dict[str, str]:
        """The address fields as typed: one text per field."""
        return {field: join_addresses(getattr(self, field)) for field in ADDRESS_FIELDS}


def split_addresses(text: str) -> list[str]:
    """Addresses typed in one field, separated by commas or semicolons (as upstream)."""
    return [part.strip() for part in _SEPARATORS.split(text or "") if part.strip()]


def join_addresses(addresses: Iterable[str]) -> str:
    return ", ".join(addresses)


def _prefixed(prefix: str, subject: str) -> str:
    return subject if subject.lower().startswith(prefix.lower()) else f"{prefix} {subject}"


def _without(addresses: Iterable[str], *excluded: str) -> tuple[str, ...]:
    """Addresses minus `excluded` (case-insensitive), without repeats, in order."""
    first: dict[str, str] = {}  # each address as first written, by its case-folded form
    for address in addresses:
        first.setdefault(address.casefold(), address)
    left_out = {e.casefold() for e in excluded}
    return tuple(address for key, address in first.items() if key not in left_out)


def _quoted(email: Email) -> str:
    quoted = "\n".join(f"> {line}" if line else ">" for line in email.body.splitlines())
    who = f"{email.sender_name} <{email.sender_email}>" if email.sender_email else email.sender_name
    return f"\n\nOn {clock_time(email.arrived_at)}, {who} wrote:\n{quoted}"


def _forwarded(email: Email) -> str:
    lines = [
        "",
        "",
        "---------- Forwarded message ----------",
        f"From: {email.sender_name} <{email.sender_email}>",
        f"To: {join_addresses(email.to)}",
    ]
    if email.cc:
        lines.append(f"Cc: {join_addresses(email.cc)}")
    lines += [f"Subject: {email.subject}", "", email.body]
    return "\n".join(lines)


def prefill(mail: Mail, mode: str, email_id: str | None) -> Composition:
    """The compose form for `mode` about message `email_id` (ActionRejected 404 if absent)."""
    if mode == "new" or email_id is None:
        return Composition()
    email = existing_email(mail, email_id)
    me = mail.self_email
    # Replying to one's own sent mail goes to its recipients, not back to oneself.
    own = email.sender_email.casefold() == me.casefold()
    reply_to = email.to if own else (email.sender_email,)
    if mode == "reply":
        return Composition(
            mode, to=reply_to, subject=_prefixed("Re:", email.subject), body=_quoted(email)
        )
    if mode == "reply_all":
        return Composition(
            mode,
            to=_without((*reply_to, *email.to), me),
            cc=_without(email.cc, me, *reply_to, *email.to),
            subject=_prefixed("Re:", email.subject),
            body=_quoted(email),
        )
    if mode == "forward":  # a forward carries the message's attachments, as in Outlook
        return Composition(
            mode,
            subject=_prefixed("Fwd:", email.subject),
            body=_forwarded(email),
            attachments=tuple(a.id for a in email.attachments),
        )
    if mode != "draft":
        raise ActionRejected(f"unknown compose mode {mode!r}; allowed: {', '.join(COMPOSE_MODES)}")
    if mail.folder_of(email.id) != "drafts":
        raise ActionRejected(f"email {email.id!r} is not a draft")
    return Composition(
        mode,
        to=email.to,
        cc=email.cc,
        bcc=email.bcc,
        subject=email.subject,
        body=email.body,
        attachments=tuple(a.id for a in email.attachments),
        draft_id=email.id,
    )
