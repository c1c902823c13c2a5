"""MicroChat's registration with the core: scenario events, baselines, evaluation tables.

Scenario events (SentinelBench format):
- `preload_messages {message_ids, call_ids?}` — history already in the chats and the call log
  (`["*"]` = the whole catalog table). The first one also loads every catalog conversation and
  team. Baselines are measured right after it applies.
- `new_message {message_id}` — one message arriving now (read state from the catalog).
- `new_call {call_id}` — one call appearing in the call log.
"""

from __future__ import annotations

import sqlite3
from collections.abc import Mapping
from types import MappingProxyType

from pydantic import Field

from apps.kit.legacy_tables import Table
from apps.microchat import state as chats
from apps.microchat.actions import ACTIONS
from apps.microchat.bench import sample_pages
from apps.microchat.catalog import (
    catalog_call,
    catalog_conversations,
    catalog_message,
    catalog_teams,
)
from apps.microchat.state import ENVIRONMENT, Chat, empty_chat
from events.registry import Environment, EventType, ImplicitAction, LoggedEvent, Measure, timeless
from events.schemas import Payload

BASELINES: Mapping[str, Measure] = MappingProxyType(
    {
        name: timeless(count)
        for name, count in {
            "unread_count": chats.unread_count,
            "unread_conversation_count": chats.unread_conversation_count,
            "mention_count": chats.mention_count,
            "urgent_count": chats.urgent_count,
            "missed_call_count": chats.missed_call_count,
            "total_message_count": chats.total_message_count,
        }.items()
    }
)


def deliver_messages(chat: Chat, message_ids: list[str], *, at: float, preloaded: bool) -> Chat:
    """Put catalog messages in their conversations. An id already delivered is the same
    message twice: left as it is (no duplicate, nothing the user did undone). Ids missing from
    the catalog are skipped; scenario validation reports them to the author."""
    arrivals = []
    for message_id in dict.fromkeys(message_ids):
        if chat.has_message(message_id):
            continue
        arrival = catalog_message(
            chat.catalog, message_id, at=at, preloaded=preloaded, self_id=chat.self_id
        )
        if arrival is not None:
            arrivals.append(arrival)
    return chats.with_messages(chat, arrivals) if arrivals else chat


def deliver_calls(chat: Chat, call_ids: list[str], *, at: float | None) -> Chat:
    calls = [
        call
        for call_id in dict.fromkeys(call_ids)
        if call_id not in chat.calls
        and (call := catalog_call(chat.catalog, call_id, at=at)) is not None
    ]
    return chats.with_calls(chat, calls) if calls else chat


def reduce_preload_messages(chat: Chat, event: LoggedEvent) -> Chat:
    """The workspace (on the first preload), the history and the call log."""
    if not chat.conversations:
        chat = chats.with_workspace(
            chat,
            catalog_conversations(chat.catalog, chat.self_id),
            catalog_teams(chat.catalog),
        )
    catalog = chat.catalog
    message_ids = catalog.expand(ENVIRONMENT, "messages", event.payload.get("message_ids"))
    call_ids = catalog.expand(ENVIRONMENT, "calls", event.payload.get("call_ids"))
    chat = deliver_messages(chat, message_ids, at=event.at, preloaded=True)
    return deliver_calls(chat, call_ids, at=None)


def reduce_new_message(chat: Chat, event: LoggedEvent) -> Chat:
    return deliver_messages(chat, [event.payload["message_id"]], at=event.at, preloaded=False)


def reduce_new_call(chat: Chat, event: LoggedEvent) -> Chat:
    return deliver_calls(chat, [event.payload["call_id"]], at=event.at)


class PreloadMessages(Payload):
    message_ids: list[str] = Field(description='catalog message ids; ["*"] = every message')
    call_ids: list[str] | None = Field(None, description='catalog call ids; ["*"] = every call')


class NewMessage(Payload):
    message_id: str = Field(description="catalog message id")


class NewCall(Payload):
    call_id: str = Field(description="catalog call id")


EVENT_TYPES: Mapping[str, EventType] = MappingProxyType(
    {
        "preload_messages": EventType(
            schema=PreloadMessages,
            reduce=reduce_preload_messages,
            help="Chat history and call log at the start (the first also loads every "
            "conversation and team); baselines are measured after it.",
            catalog_refs={"message_ids": "messages", "call_ids": "calls"},
            preload=True,
        ),
        "new_message": EventType(
            schema=NewMessage,
            reduce=reduce_new_message,
            help="One message arrives in its conversation.",
            catalog_refs={"message_id": "messages"},
        ),
        "new_call": EventType(
            schema=NewCall,
            reduce=reduce_new_call,
            help="One call appears in the call log.",
            catalog_refs={"call_id": "calls"},
        ),
    }
)


# --- evaluation tables (the original's names and columns, so eval_sql runs unchanged) ----------

MESSAGES = Table(
    "messages",
    (
        "id TEXT PRIMARY KEY",
        "conversationId TEXT",
        "senderId TEXT",
        "content TEXT",
        "isUrgent INTEGER",
        "mentionsMe INTEGER",
        "hasAttachment INTEGER",
    ),
)
MESSAGE_STATES = Table("message_states", ("message_id TEXT PRIMARY KEY", "isRead INTEGER"))
CONVERSATIONS = Table(
    "conversations", ("id TEXT PRIMARY KEY", "name TEXT", "type TEXT", "teamId TEXT")
)
CONVERSATION_STATES = Table(
    "conversation_states",
    ("conversation_id TEXT PRIMARY KEY", "isPinned INTEGER", "isMuted INTEGER"),
)
TEAMS = Table("teams", ("id TEXT PRIMARY KEY", "name TEXT"))
CALLS = Table("calls", ("id TEXT PRIMARY KEY", "callerId TEXT", "missed INTEGER", "duration TEXT"))
# Ours: what the agent wrote. The original kept sent messages in the browser only; they stay out
# of `messages`, so typing a watched phrase into a chat can never satisfy a content check.
SENT_MESSAGES = Table(
    "sent_messages",
    ("id TEXT PRIMARY KEY", "conversationId TEXT", "content TEXT", "replyToId TEXT"),
)


def materialize(chat: Chat, now: float, conn: sqlite3.Connection) -> None:
    """Write the tables (nothing in a chat moves between events: `now` is unused)."""
    received = [m for m in chat.messages.values() if not m.sent_in_run]
    MESSAGES.write(
        conn,
        (
            (
                m.id,
                m.conversation_id,
                m.sender_id,
                m.content,
                m.is_urgent,
                m.mentions_me,
                m.has_attachment,
            )
            for m in received
        ),
    )
    MESSAGE_STATES.write(conn, ((m.id, chat.read[m.id]) for m in received))
    CONVERSATIONS.write(
        conn, ((c.id, c.name, c.type, c.team_id) for c in chat.conversations.values())
    )
    CONVERSATION_STATES.write(
        conn,
        ((i, s.is_pinned, s.is_muted) for i, s in chat.conversation_states.items()),
    )
    TEAMS.write(conn, ((t.id, t.name) for t in chat.teams.values()))
    CALLS.write(conn, ((c.id, c.caller_id, c.missed, c.duration) for c in chat.calls.values()))
    SENT_MESSAGES.write(
        conn,
        (
            (m.id, m.conversation_id, m.content, m.reply_to)
            for m in chat.messages.values()
            if m.sent_in_run
        ),
    )


def opens_unread(chat: Chat, conversation_id: str) -> bool:
    return any(
        not chat.read[i] for i, m in chat.messages.items() if m.conversation_id == conversation_id
    )


MICROCHAT = Environment(
    name=ENVIRONMENT,
    title="MicroChat",
    initial_state=empty_chat,
    event_types=EVENT_TYPES,
    actions=ACTIONS,
    baselines=BASELINES,
    materialize=materialize,
    urlconf="apps.microchat.urls",
    implicit_actions=(
        # Opening a chat marks what is unread in it read, as clicking its row does in Teams.
        ImplicitAction(
            page="chat",
            param="conversation",
            action="open_conversation",
            payload=lambda conversation_id: {"conversation_id": conversation_id},
            applies=opens_unread,
        ),
    ),
    sample_pages=sample_pages,
)
