"""A page's state in its query string: every screen a stable, shareable URL.

An environment declares its screens' query as a frozen dataclass of string fields, each a
`choice(allowed, default=…, always=…, not_found=…, requires=…)`, a free `text()` or an `item()`
id (apps/micromail/query.py is the fullest example).

`from_params` validates (an `InvalidQuery` names the parameter and the allowed values; an unknown
`not_found` choice is a 404, any other a 400); `querystring()` is canonical — defaults left out,
fields in declaration order — so one screen has exactly one URL.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from functools import cached_property
from typing import Any, Self
from urllib.parse import parse_qsl, quote_plus, urlencode

MAX_TEXT_LENGTH = 200


class InvalidQuery(ValueError):
    def __init__(self, message: str, status: int = 400):
        super().__init__(message)
        self.status = status


def choice(
    allowed: tuple[str, ...],
    *,
    default: str,
    always: bool = False,
    not_found: bool = False,
    requires: str | None = None,
) -> Any:
    """One of `allowed`. `always`: kept in the URL even at its default; `not_found`: an unknown
    value is a missing page (404), not a bad request; `requires`: left out unless that field is
    set (a search scope means nothing without a search)."""
    meta = {
        "kind": "choice",
        "allowed": allowed,
        "always": always,
        "not_found": not_found,
        "requires": requires,
    }
    return dataclasses.field(default=default, metadata=meta)


def text(*, max_length: int = MAX_TEXT_LENGTH) -> Any:
    """Free text (a search), stripped and cut to `max_length`."""
    return dataclasses.field(default="", metadata={"kind": "text", "max_length": max_length})


def item() -> Any:
    """The id of an open item, or None. Declare it last: `with_item` appends it."""
    return dataclasses.field(default=None, metadata={"kind": "item"})


@dataclasses.dataclass(frozen=True)
class QueryState:
    @classmethod
    def from_params(cls, params: Mapping[str, str]) -> Self:
        """Read and validate a query (a QueryDict or a dict); InvalidQuery names the field."""
        values = {}
        for field in dataclasses.fields(cls):
            meta, raw = field.metadata, params.get(field.name)
            if meta["kind"] == "choice":
                value = raw or field.default
                if value not in meta["allowed"]:
                    raise InvalidQuery(
                        f"{field.name}={value!r} is not valid; allowed: {', '.join(meta['allowed'])}",
                        status=404 if meta["not_found"] else 400,
                    )
            elif meta["kind"] == "text":
                value = (raw or "").strip()[: meta["max_length"]]
            else:
                value = raw or None
            values[field.name] = value
        return cls(**values)

    @classmethod
    def from_querystring(cls, text: str) -> Self:
        """Parse a `back` field of a form; anything invalid falls back to the defaults."""
        try:
            return cls.from_params(dict(parse_qsl((text or "").lstrip("?"))))
        except InvalidQuery:
            return cls()

    def but(self, **changes: Any) -> Self:
        return dataclasses.replace(self, **changes)

    def querystring(self) -> str:
        """The canonical query string, starting with '?' (empty when all are defaults)."""
        return self._encode(self._params())

    def with_item(self, name: str, value: str) -> str:
        """The query string of this screen with item `name` = `value`, as
        `but(**{name: value}).querystring()` gives it, without building a new query: a list of
        rows links each row this way, encoding the rest once."""
        rest = self._without_items
        return f"{rest}{'&' if len(rest) > 1 else ''}{name}={quote_plus(value)}"

    @cached_property
    def _without_items(self) -> str:
        params = self._params()
        for field in dataclasses.fields(self):
            if field.metadata["kind"] == "item":
                params.pop(field.name, None)
        return self._encode(params) or "?"

    def _params(self) -> dict[str, str]:
        params: dict[str, str] = {}
        for field in dataclasses.fields(self):
            value, meta = getattr(self, field.name), field.metadata
            if value in (None, "") or (value == field.default and not meta.get("always")):
                continue
            if meta.get("requires") and not getattr(self, meta["requires"]):
                continue
            params[field.name] = value
        return params

    @staticmethod
    def _encode(params: dict[str, str]) -> str:
        return "?" + urlencode(params) if params else ""
