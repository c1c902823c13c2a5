"""The mailbox URL: folder, quick filter, search and open message live in the query string.

`/r/<token>/micromail/?folder=inbox&filter=unread&q=budget&scope=all&email=<id>` — every
screen is a stable, shareable URL. Defaults are left out (`filter=all`, empty `q`,
`scope=folder`), so the canonical URL of a screen is unique.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace
from functools import cached_property
from urllib.parse import parse_qsl, quote_plus, urlencode

from apps.micromail.state import FOLDERS, QUICK_FILTERS

SCOPES = ("folder", "all")  # search the current folder, or every folder
MAX_QUERY_LENGTH = 200


class InvalidQuery(ValueError):
    def __init__(self, message: str, status: int = 400):
        super().__init__(message)
        self.status = status


def _choice(params: Mapping[str, str], name: str, allowed: tuple[str, ...], default: str) -> str:
    value = params.get(name) or default
    if value not in allowed:
        raise InvalidQuery(
            f"{name}={value!r} is not valid; allowed: {', '.join(allowed)}",
            status=404 if name == "folder" else 400,
        )
    return value


@dataclass(frozen=True)
class MailboxQuery:
    folder: str = "inbox"
    filter: str = "all"
    q: str = ""
    scope: str = "folder"
    email: str | None = None

    @classmethod
    def from_params(cls, params: Mapping[str, str]) -> MailboxQuery:
        """Read and validate a query string (a QueryDict or dict); InvalidQuery names the field."""
        return cls(
            folder=_choice(params, "folder", FOLDERS, "inbox"),
            filter=_choice(params, "filter", QUICK_FILTERS, "all"),
            q=(params.get("q") or "").strip()[:MAX_QUERY_LENGTH],
            scope=_choice(params, "scope", SCOPES, "folder"),
            email=params.get("email") or None,
        )

    @classmethod
    def from_querystring(cls, text: str) -> MailboxQuery:
        """Parse a `back` field; anything invalid falls back to the inbox (never an error)."""
        try:
            return cls.from_params(dict(parse_qsl((text or "").lstrip("?"))))
        except InvalidQuery:
            return cls()

    @property
    def searches_everywhere(self) -> bool:
        return bool(self.q) and self.scope == "all"

    def but(self, **changes) -> MailboxQuery:
        return replace(self, **changes)

    def querystring(self) -> str:
        """The canonical query string, starting with '?'."""
        return self.opening(self.email) if self.email else self._list_querystring

    def opening(self, email_id: str) -> str:
        """The query string of this screen with `email_id` open, as `but(email=…)` would give:
        `email` is the last parameter, so a list of rows encodes the rest only once."""
        return f"{self._list_querystring}&email={quote_plus(email_id)}"  # as urlencode does

    @cached_property
    def _list_querystring(self) -> str:
        """This screen without an open message (frozen: computed once per query)."""
        params = {"folder": self.folder}
        if self.filter != "all":
            params["filter"] = self.filter
        if self.q:
            params["q"] = self.q
            if self.scope != "folder":
                params["scope"] = self.scope
        return "?" + urlencode(params)
