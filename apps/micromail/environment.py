"""MicroMail's registration with the core: scenario events, baselines, evaluation tables.

Scenario events (SentinelBench format):
- `preload_emails {email_ids: [...]}` — mail already in the mailbox when the task starts
  (`["*"]` = the whole `emails` catalog table). Baselines are captured right after it applies.
- `new_email {email_id}` — one message arriving now.
"""

from __future__ import annotations

import sqlite3
from collections.abc import Callable, Mapping
from dataclasses import replace
from types import MappingProxyType

from apps.micromail import state as mailbox
from apps.micromail.actions import ACTIONS
from apps.micromail.bench import sample_pages
from apps.micromail.catalog import catalog_email, catalog_state
from apps.micromail.state import ENVIRONMENT, Mail, empty_mail, with_emails
from events.registry import Environment, EventType, Field, LoggedEvent

# Upstream stamps preloaded mail "five minutes before start", so the list reads "5 min ago".
PRELOAD_AGE_S = 300.0

BASELINES: Mapping[str, Callable[[Mail], int]] = MappingProxyType(
    {
        "unread_count": mailbox.unread_count,
        "junk_count": mailbox.junk_count,
        "attachment_count": mailbox.attachment_count,
        "external_count": mailbox.external_count,
        "inbox_count": mailbox.inbox_count,
        "urgent_count": mailbox.urgent_count,
        "mention_count": mailbox.mention_count,
        "cc_count": mailbox.cc_count,
    }
)


def measure_baselines(mail: Mail) -> Mapping[str, int]:
    return MappingProxyType({name: measure(mail) for name, measure in BASELINES.items()})


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
    """Preload mail (keeping its catalog read state), then capture the baselines.

    Like upstream, each preload replaces the baselines, so they describe the mailbox right after
    the last preload.
    """
    ids = mail.catalog.expand(ENVIRONMENT, "emails", event.payload["email_ids"])
    mail = deliver(mail, ids, arrived_at=event.at - PRELOAD_AGE_S, preloaded=True)
    return replace(mail, baselines=measure_baselines(mail))


def reduce_new_email(mail: Mail, event: LoggedEvent) -> Mail:
    """A message arrives unread, stamped with the event's simulated time."""
    return deliver(mail, [event.payload["email_id"]], arrived_at=event.at, preloaded=False)


EVENT_TYPES: Mapping[str, EventType] = MappingProxyType(
    {
        "preload_emails": EventType(
            schema={"email_ids": Field(list, help='catalog email ids; ["*"] = every email')},
            reduce=reduce_preload_emails,
            help="Mail already in the mailbox at the start; baselines are measured after it.",
            catalog_refs={"email_ids": "emails"},
        ),
        "new_email": EventType(
            schema={"email_id": Field(str, help="catalog email id")},
            reduce=reduce_new_email,
            help="One message arrives, unread.",
            catalog_refs={"email_id": "emails"},
        ),
    }
)


# --- evaluation tables (upstream names and columns, so eval_sql runs unchanged) -----------------

EMAILS_DDL = """CREATE TABLE emails (
    id TEXT PRIMARY KEY, subject TEXT, sender_name TEXT, sender_email TEXT,
    hasAttachment INTEGER, isExternal INTEGER, importance TEXT, mentionsMe INTEGER,
    isCC INTEGER, body TEXT, attachment_name TEXT)"""
EMAIL_STATES_DDL = """CREATE TABLE email_states (
    email_id TEXT PRIMARY KEY, isRead INTEGER, isFlagged INTEGER, isPinned INTEGER, folder TEXT)"""


def materialize(mail: Mail, conn: sqlite3.Connection) -> None:
    """Write `emails` and `email_states`; booleans as 0/1, all attachment names in one column."""
    conn.execute(EMAILS_DDL)
    conn.execute(EMAIL_STATES_DDL)
    conn.executemany(
        "INSERT INTO emails VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
        [
            (
                e.id,
                e.subject,
                e.sender_name,
                e.sender_email,
                int(e.has_attachment),
                int(e.is_external),
                e.importance,
                int(e.mentions_me),
                int(e.is_cc),
                e.body,
                e.attachment_names,
            )
            for e in mail.emails.values()
        ],
    )
    conn.executemany(
        "INSERT INTO email_states VALUES (?, ?, ?, ?, ?)",
        [
            (email_id, int(s.is_read), int(s.is_flagged), int(s.is_pinned), s.folder)
            for email_id, s in mail.states.items()
        ],
    )


MICROMAIL = Environment(
    name=ENVIRONMENT,
    title="MicroMail",
    initial_state=empty_mail,
    event_types=EVENT_TYPES,
    actions=ACTIONS,
    baselines=lambda mail: mail.baselines,
    materialize=materialize,
    urlconf="apps.micromail.urls",
    catalog_tables=("emails",),
    sample_pages=sample_pages,
)
