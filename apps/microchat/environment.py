"""MicroChat's registration with the core: scenario events (SentinelBench's `preload_messages`,
`new_message`, `new_call`: their help says what each does), baselines, evaluation tables."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from pydantic import Field

from apps.kit.arrivals import Delivery, Stamp, arrival, event_types, preload
from apps.kit.counts import ShownCount, untimed
from apps.kit.deciding import opening
from apps.kit.environments import declare
from apps.kit.retractions import retraction, window
from apps.kit.tables import KEY, VALUE, Table, named, tables
from apps.microchat import state as chats
from apps.microchat.catalog import catalog_message, make_call, make_conversation, make_team
from apps.microchat.state import ENVIRONMENT, Chat, Message, with_messages
from events.registry import counted
from events.schemas import Payload

BASELINES = counted(
    {
        "unread_count": chats.unread_count,
        "unread_conversation_count": chats.unread_conversation_count,
        "mention_count": chats.mention_count,
        "urgent_count": chats.urgent_count,
        "missed_call_count": chats.missed_call_count,
        "total_message_count": chats.total_message_count,
    }
)


def deliver_messages(chat: Chat, ids: Iterable[str], at: float, *, preloaded: bool) -> Chat:
    """Put catalog messages in their conversations, each with the read state and reactions the
    catalog gives it (three mappings: more than a `Delivery` fills). An id already delivered is
    left as it is; one missing from the catalog is skipped."""
    new = [i for i in dict.fromkeys(ids) if i not in chat.messages]
    made = (catalog_message(chat, i, Stamp(at, preloaded, n)) for n, i in enumerate(new))
    arrivals = [arrived for arrived in made if arrived is not None]
    return with_messages(chat, arrivals)


deliver_calls = Delivery("calls", make_call)
deliver_conversations = Delivery("conversations", make_conversation, states="conversation_states")
deliver_teams = Delivery("teams", make_team)


class PreloadMessages(Payload):
    # `call_ids` is optional and may be null (none), as it always was; `message_ids` is declared
    # (again) by `preload` below and named here only to stay the first field of the schema.
    message_ids: list[str]
    call_ids: list[str] | None = Field(None, description='catalog call ids; ["*"] = every call')


def workspace_and_calls(chat: Chat, payload: Mapping[str, Any], at: float) -> Chat:
    """Every conversation and team of the catalog (the first preload brings them; later ones
    find them there), then the call log."""
    catalog = chat.catalog
    for deliver, table in ((deliver_conversations, "conversations"), (deliver_teams, "teams")):
        chat = deliver(chat, catalog.table(ENVIRONMENT, table), at, preloaded=True)
    calls = catalog.expand(ENVIRONMENT, "calls", payload.get("call_ids"))
    return deliver_calls(chat, calls, at, preloaded=True)


EVENT_TYPES = event_types(
    preload(
        "preload_messages",
        {"message_ids": ("messages", deliver_messages)},
        required=("message_ids",),
        base=PreloadMessages,
        then=workspace_and_calls,
        refs={"call_ids": "calls"},
        environment=ENVIRONMENT,
        help="Chat history and call log at the start (the first also loads every "
        "conversation and team); baselines are measured after it.",
    ),
    arrival(
        "new_message",
        "message_id",
        "messages",
        deliver_messages,
        help="One message arrives in its conversation.",
    ),
    arrival(
        "new_call", "call_id", "calls", deliver_calls, help="One call appears in the call log."
    ),
    retraction(
        "unsend_message",
        "message_id",
        "messages",
        "messages",
        help='Its sender deletes a message: "This message has been deleted." takes its place.',
    ),
)


# --- evaluation tables (the original's names and columns, so eval_sql runs unchanged) ----------
# Nothing in a chat moves between events: `now` is unused.


def received(chat: Chat, now: float) -> Iterable[Message]:
    return (m for m in chat.messages.values() if not m.sent_in_run)


materialize = tables(
    Table(
        "messages",
        received,
        {
            "id TEXT PRIMARY KEY": "id",
            "conversationId TEXT": "conversation_id",
            "senderId TEXT": "sender_id",
            "content TEXT": "content",
            "isUrgent INTEGER": "is_urgent",
            "mentionsMe INTEGER": "mentions_me",
            "hasAttachment INTEGER": "has_attachment",
            **window("sent_at"),
        },
    ),
    Table.keyed(
        "message_states",
        lambda chat, now: {m.id: chat.read[m.id] for m in received(chat, now)},
        {"message_id TEXT PRIMARY KEY": KEY, "isRead INTEGER": VALUE},
    ),
    Table.items(
        "conversations",
        {**named("id TEXT PRIMARY KEY", "name TEXT", "type TEXT"), "teamId TEXT": "team_id"},
    ),
    Table.keyed(
        "conversation_states",
        "conversation_states",
        {
            "conversation_id TEXT PRIMARY KEY": KEY,
            "isPinned INTEGER": "is_pinned",
            "isMuted INTEGER": "is_muted",
        },
    ),
    Table.items("teams", named("id TEXT PRIMARY KEY", "name TEXT")),
    Table.items(
        "calls",
        {
            "id TEXT PRIMARY KEY": "id",
            "callerId TEXT": "caller_id",
            "missed INTEGER": "missed",
            "duration TEXT": "duration",
        },
    ),
    # Ours: what the agent wrote. The original kept sent messages in the browser only; they stay
    # out of `messages`, so typing a watched phrase into a chat can never satisfy a content check.
    Table(
        "sent_messages",
        lambda chat, now: (m for m in chat.messages.values() if m.sent_in_run),
        {
            "id TEXT PRIMARY KEY": "id",
            "conversationId TEXT": "conversation_id",
            "content TEXT": "content",
            "replyToId TEXT": "reply_to",
        },
    ),
)


def has_unread(chat: Chat, conversation_id: str) -> bool:
    return bool(chats.unread_in(chat, conversation_id))


# The numbers shown in more than one place (apps.kit.counts): the rail's badges on every screen,
# the call log's tabs.
SHOWN_COUNTS = (
    ShownCount(
        "unread chats",
        untimed(chats.unread_conversation_count),
        ("{n} unread chats?",),
    ),
    ShownCount(
        "missed calls",
        untimed(chats.missed_call_count),
        ("Activity {n} new", r"All [\d,]+ Missed {n}"),
    ),
    ShownCount("calls", lambda chat, now: len(chat.calls), ("All {n} Missed",)),
)


IMPLICIT_ACTIONS = (
    # Opening a chat marks what is unread in it read, as clicking its row does in Teams.
    opening("chat", "conversation", "open_conversation", "conversation_id", applies=has_unread),
)


MICROCHAT = declare(__name__, title="MicroChat", initial_state=Chat.of)
