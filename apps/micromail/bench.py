"""The MicroMail pages worth timing (`manage.py bench_pages --env micromail`), from the state:
every folder and quick filter, searches, an open message, each compose form, a preview."""

from __future__ import annotations

import re

from apps.micromail import state as mailbox
from apps.micromail.query import MailboxQuery
from apps.micromail.screens import compose_url
from apps.micromail.state import FOLDERS, QUICK_FILTERS, Mail

_WORD = re.compile(r"[A-Za-z]{5,}")


def _search_word(mail: Mail, email_id: str) -> str:
    """A word from a real subject, so the search page lists something."""
    words = _WORD.findall(mail.emails[email_id].subject)
    return max(words, key=len).lower() if words else "the"


def sample_pages(mail: Mail) -> list[str]:
    """One path per kind of MicroMail page (opening the newest inbox message marks it read)."""
    pages = [MailboxQuery(folder=folder).querystring() for folder in FOLDERS]
    pages += [MailboxQuery(filter=name).querystring() for name in QUICK_FILTERS if name != "all"]
    pages.append(compose_url("", "new"))
    inbox = mailbox.select(mail, folder="inbox")
    if not inbox:
        return pages
    newest = inbox[0]
    word = _search_word(mail, newest)
    pages += [
        MailboxQuery(q=word).querystring(),
        MailboxQuery(q=word, scope="all").querystring(),
        MailboxQuery(email=newest).querystring(),
        *(compose_url("", mode, newest) for mode in ("reply", "reply_all", "forward")),
    ]
    attached = next((i for i in inbox if mail.emails[i].attachments), None)
    if attached is not None:  # an attachment preview over its message
        first = mail.emails[attached].attachments[0].id
        pages.append(MailboxQuery(email=attached, preview=first).querystring())
    return pages
