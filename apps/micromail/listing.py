"""What the mailbox screen shows for a URL: folder links, filter chips, rows, the open message.

A pure function of (mail, query, root), so templates only lay things out and tests can check
the screen without HTML. The folder links are the sidebar every page shares (views.base_context),
so they are not part of the screen.
"""

from __future__ import annotations

from dataclasses import dataclass
from urllib.parse import urlencode

from apps.micromail import state as mailbox
from apps.micromail.query import MailboxQuery
from apps.micromail.state import FOLDER_TITLES, FOLDERS, Email, EmailState, Mail
from events.derived import per_state

FILTER_LABELS = {"all": "All", "unread": "Unread", "flagged": "Flagged", "mentions": "Mentions"}


@dataclass(frozen=True)
class FolderLink:
    folder: str
    title: str
    badge: int  # 0 = hidden
    url: str
    current: bool


@dataclass(frozen=True)
class FilterChip:
    name: str
    label: str
    count: int | None  # None for "All", which shows no count
    url: str
    current: bool


@dataclass(frozen=True)
class Row:
    email: Email
    state: EmailState
    url: str
    opened: bool  # the message shown in the reading pane


@dataclass(frozen=True)
class OpenEmail:
    email: Email
    state: EmailState
    written_by_self: bool  # show Bcc, which only the sender may see
    move_targets: tuple[str, ...]


@dataclass(frozen=True)
class Screen:
    query: MailboxQuery
    heading: str
    chips: tuple[FilterChip, ...]
    rows: tuple[Row, ...]
    opened: OpenEmail | None
    close_url: str  # the same list without an open message
    back: str  # query string that actions return to


def compose_url(root: str, mode: str, email_id: str | None = None) -> str:
    params = {"mode": mode, **({"email": email_id} if email_id else {})}
    return f"{root}compose?{urlencode(params)}"


def row_url(root: str, query: MailboxQuery, email_id: str, state: EmailState) -> str:
    # A draft opens in the compose form, as in the original client.
    if state.folder == "drafts":
        return compose_url(root, "draft", email_id)
    return root + query.opening(email_id)


def heading(query: MailboxQuery) -> str:
    title = FOLDER_TITLES[query.folder]
    if not query.q:
        return title
    where = "all folders" if query.searches_everywhere else title
    return f"Results for “{query.q}” in {where}"


@per_state()
def folder_links(mail: Mail, current: str | None, root: str) -> tuple[FolderLink, ...]:
    badges = mailbox.folder_badges(mail)
    return tuple(
        FolderLink(
            folder,
            FOLDER_TITLES[folder],
            badges[folder],
            root + MailboxQuery(folder=folder).querystring(),
            folder == current,
        )
        for folder in FOLDERS
    )


@per_state()
def mailbox_screen(mail: Mail, query: MailboxQuery, root: str) -> Screen:
    """The screen for `query`; `query.email` must be in the mailbox (the view checks)."""
    folder = None if query.searches_everywhere else query.folder
    searched = [
        i
        for i in mailbox.in_folder(mail, folder)
        if mailbox.matches_search(mail.emails[i], query.q)
    ]
    counts = mailbox.filter_counts(mail, searched)
    chips = tuple(
        FilterChip(
            name,
            FILTER_LABELS[name],
            None if name == "all" else counts[name],
            root + query.but(filter=name, email=None).querystring(),
            name == query.filter,
        )
        for name in mailbox.QUICK_FILTERS
    )
    ids = mailbox.select(
        mail, folder=folder, quick_filter=query.filter, query=query.q, keep=query.email
    )
    rows = tuple(
        Row(
            mail.emails[i],
            mail.states[i],
            row_url(root, query, i, mail.states[i]),
            i == query.email,
        )
        for i in ids
    )
    opened = None
    if query.email:
        email, email_state = mail.emails[query.email], mail.states[query.email]
        opened = OpenEmail(
            email=email,
            state=email_state,
            written_by_self=email_state.folder in ("sent", "drafts")
            or email.sender_email.casefold() == mail.self_email.casefold(),
            move_targets=tuple(f for f in FOLDERS if f != email_state.folder),
        )
    return Screen(
        query=query,
        heading=heading(query),
        chips=chips,
        rows=rows,
        opened=opened,
        close_url=root + query.but(email=None).querystring(),
        back=query.querystring(),
    )
