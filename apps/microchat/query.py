"""The screens' URL state: every screen a stable, shareable URL.

Chat:     `/r/<token>/microchat/?filter=unread&find=deploy&reply=<id>&conversation=<id>`
Search:   `/r/<token>/microchat/search?q=invoice`
Calendar: `/r/<token>/microchat/calendar?view=week&offset=1`
Calls:    `/r/<token>/microchat/calls?filter=missed`
"""

from __future__ import annotations

from dataclasses import dataclass

from apps.kit.query import QueryState, choice, item, text

CHAT_FILTERS = ("all", "unread", "chats", "meetings")
CALENDAR_VIEWS = ("day", "week", "month")
CALL_FILTERS = ("all", "missed")
OFFSETS = tuple(str(n) for n in range(-8, 9))  # pages of days / weeks / months from today


@dataclass(frozen=True)
class ChatQuery(QueryState):
    filter: str = choice(CHAT_FILTERS, default="all")
    find: str = text()  # search inside the open conversation
    reply: str = text()  # the message the composer answers
    conversation: str | None = item()


@dataclass(frozen=True)
class SearchQuery(QueryState):
    q: str = text()


@dataclass(frozen=True)
class CalendarQuery(QueryState):
    view: str = choice(CALENDAR_VIEWS, default="week")
    offset: str = choice(OFFSETS, default="0")


@dataclass(frozen=True)
class CallsQuery(QueryState):
    filter: str = choice(CALL_FILTERS, default="all")
