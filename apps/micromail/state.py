"""The mailbox as immutable values (`Mail`, which reducers build and pages, baselines and
evaluation read), and the questions they ask of it: pure functions of a `Mail`."""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, replace
from types import MappingProxyType
from typing import ClassVar

from apps.kit.records import flag, from_catalog, text, text_or
from apps.kit.state import SelfUserState
from apps.kit.streaming import no_items

ENVIRONMENT = "micromail"

FOLDERS: tuple[str, ...] = ("inbox", "sent", "drafts", "archive", "junk", "deleted", "scheduled")
FOLDER_TITLES: Mapping[str, str] = MappingProxyType(
    {
        "inbox": "Inbox",
        "sent": "Sent Items",
        "drafts": "Drafts",
        "archive": "Archive",
        "junk": "Junk Email",
        "deleted": "Deleted Items",
        "scheduled": "Scheduled",
    }
)
QUICK_FILTERS: tuple[str, ...] = ("all", "unread", "flagged", "mentions")
# The original's Favorites section, top of the folder pane; the user may add and remove folders.
DEFAULT_FAVORITES: tuple[str, ...] = ("inbox", "sent", "archive", "deleted")
PREVIEW_LENGTH = 140


@dataclass(frozen=True)
class Attachment:
    id: str
    name: str = from_catalog(text("name"))
    size: str = from_catalog(text("size"))


@dataclass(frozen=True)
class Email:
    """The immutable content of one message (what upstream calls the email row)."""

    id: str
    subject: str = from_catalog(text("subject"))
    body: str = from_catalog(text("body"))
    sender_name: str
    sender_email: str
    to: tuple[str, ...]
    cc: tuple[str, ...] = ()
    bcc: tuple[str, ...] = ()  # only ever set on mail the self user wrote
    is_cc: bool = from_catalog(flag("isCC"), default=False)
    has_attachment: bool = False
    is_external: bool = from_catalog(flag("isExternal"), default=False)
    # "high" | "normal" | "low"
    importance: str = from_catalog(text_or("importance", "normal"), default="normal")
    mentions_me: bool = from_catalog(flag("mentionsMe"), default=False)
    attachments: tuple[Attachment, ...] = ()
    arrived_at: float = 0.0  # simulated seconds, authored scale
    gone_at: float | None = None  # recalled by its sender then (apps.kit.retractions)

    @property
    def preview(self) -> str:
        """First 140 characters of the body on one line, as the message list shows it."""
        return " ".join(self.body.split())[:PREVIEW_LENGTH]

    @property
    def attachment_names(self) -> str:
        """Every attachment name joined with ", " ('' when none): the eval column."""
        return ", ".join(a.name for a in self.attachments)


@dataclass(frozen=True)
class EmailState:
    """What the user can change about a message."""

    folder: str = "inbox"
    is_read: bool = False
    is_flagged: bool = from_catalog(flag("isFlagged"), default=False)
    is_pinned: bool = from_catalog(flag("isPinned"), default=False)


@dataclass(frozen=True)
class Mail(SelfUserState):
    # Used only when a catalog has no user marked isSelf (e.g. a minimal test catalog).
    FALLBACK: ClassVar[Mapping[str, str]] = MappingProxyType(
        {"name": "Me", "email": "me@micromail.local"}
    )
    emails: Mapping[str, Email] = no_items()  # in delivery order
    states: Mapping[str, EmailState] = no_items()
    favorites: tuple[str, ...] = DEFAULT_FAVORITES  # folders, in the order they were added

    def has(self, email_id: str) -> bool:
        return email_id in self.emails

    def folder_of(self, email_id: str) -> str:
        return self.states[email_id].folder


# --- building new states (used by reducers only) --------------------------------------------


def with_favorite(mail: Mail, folder: str, *, on: bool) -> Mail:
    """Add `folder` to the end of Favorites, or take it out; already so: `mail` itself."""
    if (folder in mail.favorites) == on:
        return mail
    kept = tuple(f for f in mail.favorites if f != folder)
    return replace(mail, favorites=(*kept, folder) if on else kept)


def attachment_shelf(mail: Mail) -> tuple[Attachment, ...]:
    """Every document attached to mail in the mailbox, newest mail first, one per id: what the
    compose form offers to attach (mail not arrived yet shows nothing, purged mail neither)."""
    shelf: dict[str, Attachment] = {}
    for email_id in newest_first(mail, mail.emails):
        for attachment in mail.emails[email_id].attachments:
            shelf.setdefault(attachment.id, attachment)
    return tuple(shelf.values())


# --- counts (baselines and badges) ---------------------------------------------------------------


def in_mailbox(mail: Mail) -> Iterable[tuple[str, EmailState]]:
    """(id, state) of every message there: a recalled one has left every folder and count."""
    emails = mail.emails
    return ((i, s) for i, s in mail.states.items() if emails[i].gone_at is None)


def counting(predicate: Callable[[Email, EmailState], bool]) -> Callable[[Mail], int]:
    return lambda mail: sum(1 for i, s in in_mailbox(mail) if predicate(mail.emails[i], s))


# Upstream's definitions (eval_sql reads them as baselines); unread_count is also the Inbox badge.
inbox_count = counting(lambda e, s: s.folder == "inbox")
unread_count = counting(lambda e, s: s.folder == "inbox" and not s.is_read)
junk_count = counting(lambda e, s: s.folder == "junk")
attachment_count = counting(lambda e, s: e.has_attachment and s.folder != "deleted")
external_count = counting(lambda e, s: e.is_external and s.folder == "inbox")
urgent_count = counting(lambda e, s: e.importance == "high" and s.folder == "inbox")
mention_count = counting(lambda e, s: e.mentions_me and s.folder == "inbox")
cc_count = counting(lambda e, s: e.is_cc and s.folder == "inbox")


def folder_badges(mail: Mail) -> dict[str, int]:
    """Sidebar badges: Inbox shows its unread count, every other folder its total."""
    totals = Counter(s.folder for _, s in in_mailbox(mail))
    return {folder: totals[folder] for folder in FOLDERS} | {"inbox": unread_count(mail)}


# --- listing: folder, quick filter, search, order --------------------------------------------


def matches_filter(mail: Mail, email_id: str, quick_filter: str) -> bool:
    email_state = mail.states[email_id]
    return {
        "unread": not email_state.is_read,
        "flagged": email_state.is_flagged,
        "mentions": mail.emails[email_id].mentions_me,
    }.get(quick_filter, True)


def matches_search(email: Email, query: str) -> bool:
    """Case-insensitive substring over subject, body, sender and every address."""
    needle = query.strip().casefold()
    if not needle:
        return True
    fields = (email.subject, email.body, email.sender_name, email.sender_email)
    return any(needle in text.casefold() for text in (*fields, *email.to, *email.cc, *email.bcc))


def in_folder(mail: Mail, folder: str | None) -> list[str]:
    """Ids in `folder` in delivery order; None means every folder."""
    return [i for i, s in in_mailbox(mail) if folder is None or s.folder == folder]


def filter_counts(mail: Mail, ids: Iterable[str]) -> dict[str, int]:
    ids = list(ids)
    return {name: sum(1 for i in ids if matches_filter(mail, i, name)) for name in QUICK_FILTERS}


def newest_first(mail: Mail, ids: Iterable[str]) -> list[str]:
    """Pinned first, then newest arrival; equal times keep the later delivery on top."""
    position = {email_id: n for n, email_id in enumerate(mail.emails)}
    return sorted(
        ids,
        key=lambda i: (mail.states[i].is_pinned, mail.emails[i].arrived_at, position[i]),
        reverse=True,
    )


def select(
    mail: Mail,
    *,
    folder: str | None,
    quick_filter: str = "all",
    query: str = "",
    keep: str | None = None,
) -> list[str]:
    """The message list: folder ∩ quick filter ∩ search, ordered for display.

    `keep` (the open message) stays listed even when it stops matching the quick filter, so
    opening a message under "Unread" does not make it vanish under the reader's cursor.
    """
    chosen = [
        i
        for i in in_folder(mail, folder)
        if matches_search(mail.emails[i], query)
        and (matches_filter(mail, i, quick_filter) or i == keep)
    ]
    return newest_first(mail, chosen)
