"""MicroMail's registration with the core: scenario events, baselines, evaluation tables.

Scenario events (SentinelBench format):
- `preload_emails {email_ids: [...]}` — mail already in the mailbox when the task starts
  (`["*"]` = the whole `emails` catalog table). Baselines are captured right after it applies.
- `new_email {email_id}` — one message arriving now.
"""

from __future__ import annotations

import sqlite3
from collections.abc import Mapping
from types import MappingProxyType

from pydantic import Field

from apps.kit.tables import Table
from apps.micromail import state as mailbox
from apps.micromail.actions import ACTIONS
from apps.micromail.bench import sample_pages
from apps.micromail.catalog import catalog_email, catalog_state
from apps.micromail.state import ENVIRONMENT, Mail, empty_mail, with_emails
from events.registry import Environment, EventType, ImplicitAction, LoggedEvent, Measure, timeless
from events.schemas import Payload

# Upstream stamps preloaded mail "five minutes before start", so the list reads "5 min ago".
PRELOAD_AGE_S = 300.0

# Counted right after the preload, by the core (upstream's names: eval_sql reads baseline_<name>).
BASELINES: Mapping[str, Measure] = MappingProxyType(
    {
        name: timeless(count)
        for name, count in {
            "unread_count": mailbox.unread_count,
            "junk_count": mailbox.junk_count,
            "attachment_count": mailbox.attachment_count,
            "external_count": mailbox.external_count,
            "inbox_count": mailbox.inbox_count,
            "urgent_count": mailbox.urgent_count,
            "mention_count": mailbox.mention_count,
            "cc_count": mailbox.cc_count,
        }.items()
    }
)


def deliver(mail: Mail, email_ids: list[str], *, arrived_at: float, preloaded: bool) -> Mail:
    """Put catalog messages in the mailbox.

    An id already in the mailbox is the same message delivered twice: it is left as it is (no
    duplicate row, no reset of what the user did to it). Ids missing from the catalog are
    skipped; scenario validation reports them to the author before a run ever starts.
    """
    arrivals = []
    for email_id in dict.fromkeys(email_ids):  # de-duplicate, keep order
        if mail.has(email_id):
            continue
        email = catalog_email(
            mail.catalog, email_id, arrived_at=arrived_at, self_email=mail.self_email
        )
        if email is not None:
            arrivals.append((email, catalog_state(mail.catalog, email_id, keep_read=preloaded)))
    return with_emails(mail, arrivals) if arrivals else mail


def reduce_preload_emails(mail: Mail, event: LoggedEvent) -> Mail:
    """Preload mail, keeping its catalog read state (the core then measures the baselines)."""
    ids = mail.catalog.expand(ENVIRONMENT, "emails", event.payload["email_ids"])
    return deliver(mail, ids, arrived_at=event.at - PRELOAD_AGE_S, preloaded=True)


def reduce_new_email(mail: Mail, event: LoggedEvent) -> Mail:
    """A message arrives unread, stamped with the event's simulated time."""
    return deliver(mail, [event.payload["email_id"]], arrived_at=event.at, preloaded=False)


class PreloadEmails(Payload):
    email_ids: list[str] = Field(description='catalog email ids; ["*"] = every email')


class NewEmail(Payload):
    email_id: str = Field(description="catalog email id")


EVENT_TYPES: Mapping[str, EventType] = MappingProxyType(
    {
        "preload_emails": EventType(
            schema=PreloadEmails,
            reduce=reduce_preload_emails,
            help="Mail already in the mailbox at the start; baselines are measured after it.",
            catalog_refs={"email_ids": "emails"},
            preload=True,
        ),
        "new_email": EventType(
            schema=NewEmail,
            reduce=reduce_new_email,
            help="One message arrives, unread.",
            catalog_refs={"email_id": "emails"},
        ),
    }
)


# --- evaluation tables (upstream names and columns, so eval_sql runs unchanged) -----------------

EMAILS = Table(
    "emails",
    (
        "id TEXT PRIMARY KEY",
        "subject TEXT",
        "sender_name TEXT",
        "sender_email TEXT",
        "hasAttachment INTEGER",
        "isExternal INTEGER",
        "importance TEXT",
        "mentionsMe INTEGER",
        "isCC INTEGER",
        "body TEXT",
        "attachment_name TEXT",
    ),
)
EMAIL_STATES = Table(
    "email_states",
    (
        "email_id TEXT PRIMARY KEY",
        "isRead INTEGER",
        "isFlagged INTEGER",
        "isPinned INTEGER",
        "folder TEXT",
    ),
)


def materialize(mail: Mail, now: float, conn: sqlite3.Connection) -> None:
    """Write `emails` and `email_states` (nothing in a mailbox moves between events: `now` is
    unused); all attachment names in one column."""
    EMAILS.write(
        conn,
        (
            (
                e.id,
                e.subject,
                e.sender_name,
                e.sender_email,
                e.has_attachment,
                e.is_external,
                e.importance,
                e.mentions_me,
                e.is_cc,
                e.body,
                e.attachment_names,
            )
            for e in mail.emails.values()
        ),
    )
    EMAIL_STATES.write(
        conn,
        (
            (email_id, s.is_read, s.is_flagged, s.is_pinned, s.folder)
            for email_id, s in mail.states.items()
        ),
    )


MICROMAIL = Environment(
    name=ENVIRONMENT,
    title="MicroMail",
    initial_state=empty_mail,
    event_types=EVENT_TYPES,
    actions=ACTIONS,
    baselines=BASELINES,
    materialize=materialize,
    urlconf="apps.micromail.urls",
    implicit_actions=(
        # Opening an unread message in the mail client marks it read, as a click does.
        ImplicitAction(
            page="mailbox",
            param="email",
            action="open_email",
            payload=lambda email_id: {"email_id": email_id},
            applies=lambda mail, email_id: mail.has(email_id) and not mail.states[email_id].is_read,
        ),
    ),
    sample_pages=sample_pages,
)
