"""The mailbox URL: folder, quick filter, search and open message live in the query string.

`/r/<token>/micromail/?folder=inbox&filter=unread&q=budget&scope=all&email=<id>&preview=<att>`:
every screen is a stable, shareable URL, canonical (defaults left out, `folder` always kept).
"""

from __future__ import annotations

from dataclasses import dataclass

from apps.kit.query import QueryState, choice, item, text
from apps.micromail.state import FOLDERS, QUICK_FILTERS

SCOPES = ("folder", "all")  # search the current folder, or every folder


@dataclass(frozen=True)
class MailboxQuery(QueryState):
    folder: str = choice(FOLDERS, default="inbox", always=True, not_found=True)
    filter: str = choice(QUICK_FILTERS, default="all")
    q: str = text()
    scope: str = choice(SCOPES, default="folder", requires="q")
    email: str | None = item()
    preview: str | None = item()  # an attachment of the open message, shown over the page

    @property
    def searches_everywhere(self) -> bool:
        return bool(self.q) and self.scope == "all"

    def opening(self, email_id: str) -> str:
        """The query string of this screen with `email_id` open."""
        return self.with_item("email", email_id)
