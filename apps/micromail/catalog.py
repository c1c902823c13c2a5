"""Turning catalog records (SentinelBench format) into `Email` and `EmailState` values.

Catalog tables: `micromail/emails.jsonl` (id, sender_id, subject, body, flags, cc, folder…) and
`micromail/attachments.jsonl` (id, email_id, name, size). Unlike upstream, every attachment of
an email is kept, not only the first.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from apps.kit.records import Record, read
from apps.micromail.state import ENVIRONMENT, Attachment, Email, EmailState, Mail

UNKNOWN_SENDER = "Unknown Sender"


def _addresses(value: Any) -> tuple[str, ...]:
    if isinstance(value, str):
        return (value,) if value else ()
    return tuple(str(v) for v in value or ())


def attachments_by_email(catalog: Any) -> Mapping[str, tuple[Attachment, ...]]:
    grouped: dict[str, list[Attachment]] = {}
    for record in catalog.table(ENVIRONMENT, "attachments").values():
        attachment = read(Attachment, record, id=str(record["id"]))
        grouped.setdefault(str(record.get("email_id")), []).append(attachment)
    return {email_id: tuple(items) for email_id, items in grouped.items()}


def catalog_email(mail: Mail, email_id: str, record: Record, *, arrived_at: float) -> Email:
    """The message `email_id` (its catalog `record`) as it arrives at `arrived_at`."""
    catalog = mail.catalog
    sender = catalog.users.get(record.get("sender_id")) or {}
    attachments = catalog.index(attachments_by_email).get(email_id, ())
    has_attachment = record.get("hasAttachment")
    return read(
        Email,
        record,
        id=email_id,
        sender_name=str(sender.get("name") or UNKNOWN_SENDER),
        sender_email=str(sender.get("email") or ""),
        to=_addresses(record.get("recipients") or record.get("to")) or (mail.self_email,),
        cc=_addresses(record.get("cc")),
        has_attachment=bool(attachments) if has_attachment is None else bool(has_attachment),
        attachments=attachments,
        arrived_at=float(arrived_at),
    )


def catalog_state(record: Record, *, keep_read: bool) -> EmailState:
    """Initial flags and folder: folder from the catalog, else junk if marked junk, else inbox.

    `keep_read` keeps the catalog's isRead (preloaded history); newly delivered mail is unread.
    """
    folder = record.get("folder") or (
        "junk" if record.get("junk") or record.get("isJunk") else "inbox"
    )
    is_read = bool(record.get("isRead", False)) if keep_read else False
    return read(EmailState, record, folder=str(folder), is_read=is_read)
