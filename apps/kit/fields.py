"""The kinds of field an action payload may carry, each with its bound.

An agent writes these, so none may be unbounded: a multi-megabyte mail body or a 100,000-address
`to` list was accepted, stored in the run's log and rendered on every page that showed it. Every
text or list field of every environment's action schemas is one of these kinds (a generic test
holds every environment to it); a product's own, smaller rule (a message's length on the real
site) is a `decide` check on top, with the product's wording.
"""

from __future__ import annotations

from typing import Annotated

from pydantic import Field, StringConstraints

ID_CHARS = 200  # ids, symbols, usernames; dates and times as text
LINE_CHARS = 1_000  # one line: a subject, a title, a name, a location
TEXT_CHARS = 50_000  # free text: a mail's body, a comment, a message, a description
LIST_ITEMS = 100  # recipients, attachments, labels

ItemId = Annotated[str, StringConstraints(max_length=ID_CHARS)]
Moment = Annotated[str, StringConstraints(max_length=ID_CHARS)]  # "2026-10-13", "09:30"
Line = Annotated[str, StringConstraints(max_length=LINE_CHARS)]
Text = Annotated[str, StringConstraints(max_length=TEXT_CHARS)]
ItemIds = Annotated[list[ItemId], Field(max_length=LIST_ITEMS)]
Lines = Annotated[list[Line], Field(max_length=LIST_ITEMS)]
