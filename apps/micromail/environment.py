"""MicroMail's registration with the core: scenario events (SentinelBench's `preload_emails`
and `new_email`), baselines, evaluation tables."""

from __future__ import annotations

from apps.kit import feeds
from apps.kit.arrivals import Delivery, Stamp, arrival, event_types, preload
from apps.kit.counts import ShownCount, untimed
from apps.kit.deciding import opening
from apps.kit.environments import declare
from apps.kit.records import Record
from apps.kit.retractions import retraction, window
from apps.kit.tables import KEY, Table, named, tables
from apps.micromail import state as mailbox
from apps.micromail.catalog import catalog_email, catalog_state
from apps.micromail.state import ENVIRONMENT, FOLDER_TITLES, FOLDERS, Email, EmailState, Mail
from events.registry import counted

# Upstream stamps every preloaded mail "five minutes before start", so its list reads "5 min ago"
# throughout; our catalog dates each message (`ageMinutes`), from minutes to days before.
PRELOAD_AGE_S = 300.0

# Counted right after the preload, by the core (upstream's names: eval_sql reads baseline_<name>).
BASELINES = counted(
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


@feeds.from_catalog(ENVIRONMENT, "emails")
def make_email(mail: Mail, email_id: str, record: Record, stamp: Stamp) -> tuple[Email, EmailState]:
    """A catalog message as it arrives: preloaded mail keeps its catalog read flag and is dated
    its record's `ageMinutes` (else five minutes) before the start; new mail arrives unread,
    stamped with the event's time."""
    arrived_at = feeds.arrived_at(record, stamp, default_age_s=PRELOAD_AGE_S)
    email = catalog_email(mail, email_id, record, arrived_at=arrived_at)
    return email, catalog_state(record, keep_read=stamp.preloaded)


deliver_emails = Delivery("emails", make_email, states="states")

EVENT_TYPES = event_types(
    preload(
        "preload_emails",
        {"email_ids": ("emails", deliver_emails)},
        required=("email_ids",),
        environment=ENVIRONMENT,
        help="Mail already in the mailbox at the start; baselines are measured after it.",
    ),
    arrival("new_email", "email_id", "emails", deliver_emails, help="One message arrives, unread."),
    retraction(
        "recall_email",
        "email_id",
        "emails",
        "emails",
        help="Its sender recalls a message: it leaves every folder (opened, the reading pane "
        "says it was recalled).",
    ),
)


# --- evaluation tables (upstream names and columns, so eval_sql runs unchanged) -----------------
# Nothing in a mailbox moves between events: `now` is unused. All attachment names in one column.

materialize = tables(
    Table.items(
        "emails",
        {
            **named("id TEXT PRIMARY KEY", "subject TEXT", "sender_name TEXT", "sender_email TEXT"),
            "hasAttachment INTEGER": "has_attachment",
            "isExternal INTEGER": "is_external",
            "importance TEXT": "importance",
            "mentionsMe INTEGER": "mentions_me",
            "isCC INTEGER": "is_cc",
            "body TEXT": "body",
            "attachment_name TEXT": "attachment_names",
            **window("arrived_at"),
        },
    ),
    Table.keyed(
        "email_states",
        "states",
        {
            "email_id TEXT PRIMARY KEY": KEY,
            "isRead INTEGER": "is_read",
            "isFlagged INTEGER": "is_flagged",
            "isPinned INTEGER": "is_pinned",
            "folder TEXT": "folder",
        },
    ),
)


def unread(mail: Mail, email_id: str) -> bool:
    return mail.has(email_id) and not mail.states[email_id].is_read


# The numbers shown in more than one place (apps.kit.counts): the folder pane's badges (Inbox
# under Favorites and again in the account's folders), every other folder its item count.
SHOWN_COUNTS = (
    ShownCount("inbox unread", untimed(mailbox.unread_count), ("Inbox {n} unread",)),
    *(
        ShownCount(
            f"{folder} items",
            lambda mail, now, folder=folder: mailbox.folder_badges(mail)[folder],
            (f"{FOLDER_TITLES[folder]} {{n}} items",),
        )
        for folder in FOLDERS
        if folder != "inbox"
    ),
)


IMPLICIT_ACTIONS = (
    # Opening an unread message in the mail client marks it read, as a click does.
    opening("mailbox", "email", "open_email", "email_id", applies=unread),
)


MICROMAIL = declare(__name__, title="MicroMail", initial_state=Mail.of)
