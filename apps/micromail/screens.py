"""What the mailbox screen shows for a URL, a pure function of (mail, query, root). The folder
links are the sidebar every page shares (views.base_context), so not part of the screen."""

from __future__ import annotations

from dataclasses import dataclass
from urllib.parse import urlencode

from apps.kit.derived import per_state
from apps.micromail import state as mailbox
from apps.micromail.query import MailboxQuery
from apps.micromail.state import FOLDER_TITLES, FOLDERS, Attachment, Email, EmailState, Mail


@dataclass(frozen=True)
class FolderLink:
    folder: str
    title: str
    badge: int  # 0 = hidden
    url: str
    current: bool
    favorite: bool  # listed under Favorites too


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
class AttachmentLink:
    attachment: Attachment
    url: str  # the preview overlay's own screen


@dataclass(frozen=True)
class Preview:
    """An attachment shown over the page: a picture for images, spreadsheets and decks, the
    text for documents, a notice for the rest (archives)."""

    attachment: Attachment
    kind: str  # "picture" | "document" | "none"
    subject: str  # the picture's subject (apps/media), when kind == "picture"
    title: str
    lines: tuple[str, ...]  # the document's text, when kind == "document"
    close_url: str  # back to the message


@dataclass(frozen=True)
class OpenEmail:
    email: Email
    state: EmailState
    written_by_self: bool  # show Bcc, which only the sender may see
    move_targets: tuple[str, ...]
    attachments: tuple[AttachmentLink, ...]


@dataclass(frozen=True)
class Screen:
    query: MailboxQuery
    heading: str
    chips: tuple[FilterChip, ...]
    rows: tuple[Row, ...]
    opened: OpenEmail | None
    preview: Preview | None
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


def row_label(email: Email, state: EmailState, ago: str) -> str:
    """The row link's accessible name: read state, sender, subject, time, then the marks, each
    its own sentence ("Unread. From Maya Okonjo. Subject: Q3 budget review. 5 min ago.
    Flagged."), so a screen reader or an agent reading the name can tell the parts apart."""
    parts = [
        "Unread" if not state.is_read else "",
        f"From {email.sender_name}",
        f"Subject: {email.subject or '(no subject)'}",
        ago,
        "Flagged" if state.is_flagged else "",
        "Pinned" if state.is_pinned else "",
        {"high": "High importance", "low": "Low importance"}.get(email.importance, ""),
        "Has attachments" if email.has_attachment else "",
        "External sender" if email.is_external else "",
        "Mentions you" if email.mentions_me else "",
    ]
    return " ".join(f"{part[:1].upper()}{part[1:].rstrip('.')}." for part in parts if part)


# A file's kind by its extension: the colour of its icon (Office's: red PDF, blue Word…) and
# how its preview shows it.
FILE_KINDS = {
    "pdf": "pdf",
    **dict.fromkeys(("doc", "docx", "txt", "md", "rtf", "odt"), "doc"),
    **dict.fromkeys(("xls", "xlsx", "csv", "numbers"), "sheet"),
    **dict.fromkeys(("ppt", "pptx", "key"), "slides"),
    **dict.fromkeys(("png", "jpg", "jpeg", "gif", "webp", "svg"), "image"),
    **dict.fromkeys(("zip", "7z", "tar", "gz"), "archive"),
}
PICTURED = {"image": "screenshot", "sheet": "chart", "slides": "whiteboard"}  # apps/media subjects
DOCUMENTS = ("pdf", "doc")


def file_kind(name: str) -> str:
    extension = name.rsplit(".", 1)[-1].lower() if "." in name else ""
    return FILE_KINDS.get(extension, "file")


def document_title(name: str) -> str:
    """ "board-deck-finance_draft.pptx" → "Board deck finance draft"."""
    stem = name.rsplit(".", 1)[0] if "." in name else name
    words = " ".join(stem.replace("_", " ").replace("-", " ").split())
    return words[:1].upper() + words[1:]


def document_lines(body: str) -> tuple[str, ...]:
    """The message's paragraphs as a document's text: without the greeting ("Hi Sunita,") and
    the signature ("Tobias"), which belong to the letter, not to the document."""
    lines = [line.strip() for line in body.splitlines() if line.strip()]
    if len(lines) > 2 and lines[0].endswith(",") and len(lines[0]) <= 40:
        lines = lines[1:]
    if len(lines) > 1 and len(lines[-1].split()) <= 3 and not lines[-1].endswith((".", "?", "!")):
        lines = lines[:-1]
    return tuple(lines)


def preview_of(email: Email, attachment: Attachment, close_url: str) -> Preview:
    """How the attachment previews, by its file type. A document shows the text it came with
    (the message's paragraphs under the document's title): no file content exists."""
    kind, title = file_kind(attachment.name), document_title(attachment.name)
    if kind in PICTURED:
        return Preview(attachment, "picture", PICTURED[kind], title, (), close_url)
    if kind in DOCUMENTS:
        return Preview(attachment, "document", "", title, document_lines(email.body), close_url)
    return Preview(attachment, "none", "", title, (), close_url)


def attachment_of(email: Email, attachment_id: str | None) -> Attachment | None:
    return next((a for a in email.attachments if a.id == attachment_id), None)


def heading(query: MailboxQuery) -> str:
    title = FOLDER_TITLES[query.folder]
    if not query.q:
        return title
    where = "all folders" if query.searches_everywhere else title
    return f"Results for “{query.q}” in {where}"


@per_state()
def folder_links(mail: Mail, current: str | None, root: str) -> tuple[FolderLink, ...]:
    """Every folder of the account, in the original's order."""
    badges = mailbox.folder_badges(mail)
    return tuple(
        FolderLink(
            folder,
            FOLDER_TITLES[folder],
            badges[folder],
            root + MailboxQuery(folder=folder).querystring(),
            folder == current,
            folder in mail.favorites,
        )
        for folder in FOLDERS
    )


@per_state()
def favorite_links(mail: Mail, current: str | None, root: str) -> tuple[FolderLink, ...]:
    """The Favorites section: the favourite folders in the order they were added."""
    by_folder = {link.folder: link for link in folder_links(mail, current, root)}
    return tuple(by_folder[f] for f in mail.favorites if f in by_folder)


# What the compose form's attachment picker offers: documents of mail in the mailbox.
attachment_choices = per_state()(mailbox.attachment_shelf)


@per_state()
def mailbox_screen(mail: Mail, query: MailboxQuery, root: str) -> Screen:
    """The screen for `query`; `query.email` must be in the mailbox and `query.preview` one of
    its attachments (the view checks)."""
    folder = None if query.searches_everywhere else query.folder
    counts = mailbox.filter_counts(mail, mailbox.select(mail, folder=folder, query=query.q))
    chips = tuple(
        FilterChip(
            name,
            name.title(),  # All, Unread, Flagged, Mentions
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
    opened = preview = None
    if query.email:
        email, email_state = mail.emails[query.email], mail.states[query.email]
        message = query.but(preview=None)
        opened = OpenEmail(
            email=email,
            state=email_state,
            written_by_self=email_state.folder in ("sent", "drafts")
            or email.sender_email.casefold() == mail.self_email.casefold(),
            move_targets=tuple(f for f in FOLDERS if f != email_state.folder),
            attachments=tuple(
                AttachmentLink(a, root + message.but(preview=a.id).querystring())
                for a in email.attachments
            ),
        )
        shown = attachment_of(email, query.preview)
        if shown is not None:
            preview = preview_of(email, shown, root + message.querystring())
    return Screen(
        query=query,
        heading=heading(query),
        chips=chips,
        rows=rows,
        opened=opened,
        preview=preview,
        close_url=root + query.but(email=None, preview=None).querystring(),
        back=query.querystring(),
    )
