"""The MicroChat pages worth timing (`manage.py bench_pages --env microchat`), from the state.

A pure function of the chat: the chat list under each filter, the busiest conversation open
(with and without an in-conversation search), a global search, teams, a channel, the calendar,
calls and activity. Paths are relative to the environment root (`/r/<token>/microchat/`).
"""

from __future__ import annotations

from collections import Counter

from apps.microchat.query import CHAT_FILTERS, ChatQuery, SearchQuery
from apps.microchat.state import Chat


def sample_pages(chat: Chat) -> list[str]:
    pages = [ChatQuery(filter=name).querystring() for name in CHAT_FILTERS]
    pages += [
        "teams",
        "calendar",
        "calendar?view=month",
        "calls",
        "calls?filter=missed",
        "activity",
    ]
    if chat.teams:
        team = next(iter(chat.teams.values()))
        pages.append(f"teams/{team.id}")
    by_conversation = Counter(message.conversation_id for message in chat.messages.values())
    if by_conversation:
        busiest = max(by_conversation, key=by_conversation.__getitem__)
        word = next(iter(chat.messages.values())).content.split()[0] if chat.messages else "the"
        pages += [
            ChatQuery().with_item("conversation", busiest),
            ChatQuery(find=word).with_item("conversation", busiest),
            "search" + SearchQuery(q=word).querystring(),
        ]
    return pages
