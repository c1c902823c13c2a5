"""The chat workspace as immutable values, and the questions pages and baselines ask of it.

`Chat` is what the reducers build and what every page, baseline and evaluation reads. It is
never mutated: a reducer returns a new `Chat`. Conversations and teams come with the first
preload (all of the catalog's, as in the original); messages and calls arrive by event; what the
user changes (read, reactions, favourites, mute, own messages) lives in small mappings beside
the content.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import Any

ENVIRONMENT = "microchat"
CONVERSATION_TYPES: tuple[str, ...] = ("direct", "group", "meeting")

# Reactions by name (Teams' six quick reactions); drawn as icons, never as emoji glyphs, which
# render as empty boxes in a browser without an emoji font.
REACTIONS: tuple[str, ...] = ("like", "heart", "laugh", "celebrate", "sad", "angry")

# Used only when a catalog has no user marked isSelf (e.g. a minimal test catalog).
FALLBACK_SELF: Mapping[str, Any] = MappingProxyType({"id": "user000", "name": "Me"})
EMPTY: Mapping = MappingProxyType({})


@dataclass(frozen=True)
class Attachment:
    name: str
    kind: str = "file"  # "image" | "file"
    size: str = ""
    subject: str = "abstract"  # what an image shows (apps.media picture subject)


@dataclass(frozen=True)
class Message:
    """The content of one message; what the user changes about it is kept beside it."""

    id: str
    conversation_id: str
    sender_id: str
    sender_name: str
    content: str
    sent_at: float  # simulated seconds, authored scale
    is_urgent: bool = False
    mentions_me: bool = False
    has_attachment: bool = False
    attachments: tuple[Attachment, ...] = ()
    reply_to: str | None = None
    by_self: bool = False  # written by the self user (from the catalog or sent in the run)
    sent_in_run: bool = False  # sent by the agent: not part of the original's tables
    edited: bool = False


@dataclass(frozen=True)
class Conversation:
    id: str
    type: str  # direct | group | meeting
    name: str
    participant_ids: tuple[str, ...]
    avatar_color: str = "#5B5FC7"
    team_id: str | None = None
    order: int = 0
    # A meeting's slot on the calendar: (day offset from today, "HH:MM", minutes); None if unset.
    schedule: tuple[int, str, int] | None = None


@dataclass(frozen=True)
class ConversationState:
    is_pinned: bool = False
    is_muted: bool = False


@dataclass(frozen=True)
class Channel:
    id: str
    name: str
    description: str = ""
    unread_count: int = 0
    is_pinned: bool = False


@dataclass(frozen=True)
class Team:
    id: str
    name: str
    description: str
    member_ids: tuple[str, ...]
    owner_id: str | None
    channels: tuple[Channel, ...]
    avatar_color: str = "#5B5FC7"
    initials: str = ""
    order: int = 0


@dataclass(frozen=True)
class Call:
    id: str
    name: str
    caller_id: str | None  # the original's `callerId` column (its UI used `userId`)
    user_id: str | None
    type: str  # incoming | outgoing | group
    missed: bool
    duration: str
    time_text: str  # the catalog's own "2 hours ago" for calls already in the log
    at: float | None  # simulated arrival time of a call delivered by an event
    order: int = 0


Reactions = tuple[tuple[str, tuple[str, ...]], ...]  # ((reaction, user ids), …) in first-use order


@dataclass(frozen=True)
class Chat:
    # The catalog and self user are inputs, not state: excluded from equality so two folds of
    # the same log compare equal cheaply.
    catalog: Any = field(compare=False, repr=False)
    self_user: Mapping[str, Any] = field(
        compare=False, repr=False, default_factory=lambda: FALLBACK_SELF
    )
    conversations: Mapping[str, Conversation] = field(default_factory=lambda: EMPTY)
    conversation_states: Mapping[str, ConversationState] = field(default_factory=lambda: EMPTY)
    teams: Mapping[str, Team] = field(default_factory=lambda: EMPTY)
    messages: Mapping[str, Message] = field(default_factory=lambda: EMPTY)  # delivery order
    read: Mapping[str, bool] = field(default_factory=lambda: EMPTY)
    reactions: Mapping[str, Reactions] = field(default_factory=lambda: EMPTY)
    calls: Mapping[str, Call] = field(default_factory=lambda: EMPTY)  # delivery order

    @property
    def self_id(self) -> str:
        return str(self.self_user.get("id") or FALLBACK_SELF["id"])

    @property
    def self_name(self) -> str:
        return str(self.self_user.get("name") or FALLBACK_SELF["name"])

    def has_message(self, message_id: str) -> bool:
        return message_id in self.messages

    def has_conversation(self, conversation_id: str) -> bool:
        return conversation_id in self.conversations

    def pinned(self, conversation_id: str) -> bool:
        return self.conversation_states.get(conversation_id, ConversationState()).is_pinned

    def muted(self, conversation_id: str) -> bool:
        return self.conversation_states.get(conversation_id, ConversationState()).is_muted

    def user_name(self, user_id: str | None) -> str:
        user = self.catalog.users.get(user_id) if user_id else None
        return str(user.get("name")) if user and user.get("name") else "Unknown user"


def empty_chat(catalog: Any) -> Chat:
    return Chat(catalog=catalog, self_user=getattr(catalog, "self_user", None) or FALLBACK_SELF)


# --- building new states (reducers only) -----------------------------------------------------


def _frozen(mapping: dict) -> Mapping:
    return MappingProxyType(mapping)


def with_workspace(
    chat: Chat,
    conversations: Iterable[tuple[Conversation, ConversationState]],
    teams: Iterable[Team],
) -> Chat:
    convs, states = dict(chat.conversations), dict(chat.conversation_states)
    for conversation, conversation_state in conversations:
        convs[conversation.id] = conversation
        states[conversation.id] = conversation_state
    all_teams = dict(chat.teams)
    all_teams.update((team.id, team) for team in teams)
    return replace(
        chat,
        conversations=_frozen(convs),
        conversation_states=_frozen(states),
        teams=_frozen(all_teams),
    )


def with_messages(chat: Chat, arrivals: Iterable[tuple[Message, bool, Reactions]]) -> Chat:
    """Add messages (content, read, reactions), keeping delivery order."""
    messages, read, reactions = dict(chat.messages), dict(chat.read), dict(chat.reactions)
    for message, is_read, message_reactions in arrivals:
        messages[message.id] = message
        read[message.id] = is_read
        if message_reactions:
            reactions[message.id] = message_reactions
    return replace(
        chat, messages=_frozen(messages), read=_frozen(read), reactions=_frozen(reactions)
    )


def with_read(chat: Chat, message_ids: Iterable[str], is_read: bool) -> Chat:
    changed = [i for i in message_ids if i in chat.read and chat.read[i] != is_read]
    if not changed:
        return chat
    read = dict(chat.read)
    read.update(dict.fromkeys(changed, is_read))
    return replace(chat, read=_frozen(read))


def with_conversation_state(chat: Chat, conversation_id: str, **changes: Any) -> Chat:
    """Pin or mute a conversation; an id that is not in the workspace changes nothing."""
    if conversation_id not in chat.conversations:
        return chat
    states = dict(chat.conversation_states)
    states[conversation_id] = replace(states.get(conversation_id, ConversationState()), **changes)
    return replace(chat, conversation_states=_frozen(states))


def with_reaction(chat: Chat, message_id: str, reaction: str, user_id: str, on: bool) -> Chat:
    """Add or remove `user_id` among the reactors of `reaction`; a reaction nobody holds any
    longer disappears (the original kept a "0" chip)."""
    if message_id not in chat.messages:
        return chat
    current = dict(chat.reactions.get(message_id, ()))
    users = tuple(u for u in current.get(reaction, ()) if u != user_id)
    if on:
        users += (user_id,)
    if users:
        current[reaction] = users
    else:
        current.pop(reaction, None)
    reactions = dict(chat.reactions)
    reactions[message_id] = tuple(current.items())
    return replace(chat, reactions=_frozen(reactions))


def with_message_replaced(chat: Chat, message: Message) -> Chat:
    if message.id not in chat.messages:
        return chat
    messages = dict(chat.messages)
    messages[message.id] = message
    return replace(chat, messages=_frozen(messages))


def without_message(chat: Chat, message_id: str) -> Chat:
    if message_id not in chat.messages:
        return chat
    keep = lambda mapping: _frozen({k: v for k, v in mapping.items() if k != message_id})  # noqa: E731
    return replace(
        chat,
        messages=keep(chat.messages),
        read=keep(chat.read),
        reactions=keep(chat.reactions),
    )


def with_calls(chat: Chat, calls: Iterable[Call]) -> Chat:
    all_calls = dict(chat.calls)
    all_calls.update((call.id, call) for call in calls)
    return replace(chat, calls=_frozen(all_calls))


# --- counts (baselines, badges) ---------------------------------------------------------------


def unread_ids(chat: Chat) -> list[str]:
    return [i for i, is_read in chat.read.items() if not is_read]


def unread_count(chat: Chat) -> int:
    return len(unread_ids(chat))


def unread_conversation_count(chat: Chat) -> int:
    return len({chat.messages[i].conversation_id for i in unread_ids(chat)})


def mention_count(chat: Chat) -> int:
    """Unread messages that mention the self user (the original's definition)."""
    return sum(1 for i in unread_ids(chat) if chat.messages[i].mentions_me)


def urgent_count(chat: Chat) -> int:
    """Unread urgent messages."""
    return sum(1 for i in unread_ids(chat) if chat.messages[i].is_urgent)


def missed_call_count(chat: Chat) -> int:
    return sum(1 for call in chat.calls.values() if call.missed)


def total_message_count(chat: Chat) -> int:
    return len(chat.messages)


def unread_by_conversation(chat: Chat) -> dict[str, int]:
    counts: dict[str, int] = {}
    for message_id in unread_ids(chat):
        conversation_id = chat.messages[message_id].conversation_id
        counts[conversation_id] = counts.get(conversation_id, 0) + 1
    return counts
