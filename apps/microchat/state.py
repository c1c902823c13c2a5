"""The chat workspace as immutable values, and the questions pages and baselines ask of it.

Conversations and teams come with the first preload (all of the catalog's, as in the original);
messages and calls arrive by event; what the user changes (read, reactions, favourites, mute,
own messages) lives in small mappings beside the content.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import ClassVar

from apps.kit.records import flag, from_catalog, integer, read, text, text_or, texts
from apps.kit.state import SelfUserState, with_items
from apps.kit.streaming import counting, no_items

ENVIRONMENT = "microchat"

# Reactions by name (Teams' six quick reactions); drawn as icons, never as emoji glyphs, which
# render as empty boxes in a browser without an emoji font.
REACTIONS: tuple[str, ...] = ("like", "heart", "laugh", "celebrate", "sad", "angry")


@dataclass(frozen=True)
class Attachment:
    name: str = from_catalog(text_or("name", "Attachment"))
    kind: str = "file"  # "image" | "file"
    size: str = from_catalog(text_or("size"), default="")
    # what an image shows (apps.media picture subject)
    subject: str = from_catalog(text_or("subject", "abstract"), default="abstract")


@dataclass(frozen=True)
class Message:
    """The content of one message; what the user changes about it is kept beside it."""

    id: str
    conversation_id: str
    sender_id: str
    sender_name: str
    content: str = from_catalog(text_or("content"))
    sent_at: float  # simulated seconds, authored scale
    is_urgent: bool = from_catalog(flag("isUrgent"), default=False)
    mentions_me: bool = from_catalog(flag("mentionsMe"), default=False)
    has_attachment: bool = False
    attachments: tuple[Attachment, ...] = ()
    reply_to: str | None = None
    by_self: bool = False  # written by the self user (from the catalog or sent in the run)
    sent_in_run: bool = False  # sent by the agent: not part of the original's tables
    edited: bool = False
    gone_at: float | None = None  # deleted by its sender then (apps.kit.retractions)


@dataclass(frozen=True)
class Conversation:
    id: str
    type: str  # direct | group | meeting
    name: str
    participant_ids: tuple[str, ...]
    avatar_color: str = from_catalog(text_or("avatarColor", "#5B5FC7"), default="#5B5FC7")
    team_id: str | None = None
    order: int = from_catalog(integer("order"), default=0)
    # A meeting's slot on the calendar: (n-th working day from the run's start, "HH:MM",
    # minutes); None if unset.
    schedule: tuple[int, str, int] | None = None


@dataclass(frozen=True)
class ConversationState:
    is_pinned: bool = from_catalog(flag("isPinned"), default=False)
    is_muted: bool = from_catalog(flag("isMuted"), default=False)


@dataclass(frozen=True)
class Channel:
    id: str = from_catalog(text("id"))
    name: str = from_catalog(text_or("name"))
    description: str = from_catalog(text_or("description"), default="")
    unread_count: int = from_catalog(integer("unreadCount"), default=0)
    is_pinned: bool = from_catalog(flag("isPinned"), default=False)


@dataclass(frozen=True)
class Team:
    id: str
    name: str = from_catalog(text_or("name"))
    description: str = from_catalog(text_or("description"))
    member_ids: tuple[str, ...] = from_catalog(texts("memberIds"))
    owner_id: str | None = from_catalog(lambda r: r.get("ownerId"))
    channels: tuple[Channel, ...] = from_catalog(
        lambda r: tuple(
            read(Channel, c) for c in r.get("channels") or () if isinstance(c, dict) and "id" in c
        )
    )
    avatar_color: str = from_catalog(text_or("avatarColor", "#5B5FC7"), default="#5B5FC7")
    order: int = from_catalog(integer("order"), default=0)


@dataclass(frozen=True)
class Call:
    id: str
    name: str
    caller_id: str | None  # the original's `callerId` column (its UI used `userId`)
    type: str = from_catalog(text_or("type", "incoming"))  # incoming | outgoing | group
    missed: bool = from_catalog(flag("missed"))
    duration: str = from_catalog(text_or("duration"))
    # the catalog's own "2 hours ago" for calls already in the log
    time_text: str = from_catalog(text_or("time"))
    at: float | None  # simulated arrival time of a call delivered by an event
    order: int = from_catalog(integer("order"), default=0)


Reactions = tuple[tuple[str, tuple[str, ...]], ...]  # ((reaction, user ids), …) in first-use order


@dataclass(frozen=True)
class Chat(SelfUserState):
    # Used only when a catalog has no user marked isSelf (e.g. a minimal test catalog).
    FALLBACK: ClassVar[Mapping[str, str]] = MappingProxyType({"id": "user000", "name": "Me"})
    conversations: Mapping[str, Conversation] = no_items()
    conversation_states: Mapping[str, ConversationState] = no_items()
    teams: Mapping[str, Team] = no_items()
    messages: Mapping[str, Message] = no_items()  # delivery order
    read: Mapping[str, bool] = no_items()
    reactions: Mapping[str, Reactions] = no_items()
    calls: Mapping[str, Call] = no_items()  # delivery order

    def has_conversation(self, conversation_id: str) -> bool:
        return conversation_id in self.conversations

    def pinned(self, conversation_id: str) -> bool:
        return self.conversation_states.get(conversation_id, ConversationState()).is_pinned

    def muted(self, conversation_id: str) -> bool:
        return self.conversation_states.get(conversation_id, ConversationState()).is_muted

    def user_name(self, user_id: str | None, otherwise: str = "Unknown user") -> str:
        """A person's name from the user catalog, else `otherwise`."""
        user = self.catalog.users.get(user_id) if user_id else None
        return str(user["name"]) if user and user.get("name") else otherwise

    def called(self, user_id: str | None) -> str:
        """How the workspace names a person to the self user: "You", or their name."""
        return "You" if user_id == self.self_id else self.user_name(user_id)


# --- building new states (reducers only) -----------------------------------------------------


def with_messages(chat: Chat, arrivals: Iterable[tuple[Message, bool, Reactions]]) -> Chat:
    """Add messages (content, read, reactions), keeping delivery order."""
    arrivals = list(arrivals)
    chat = with_items(chat, "messages", ((m.id, m) for m, _, _ in arrivals))
    chat = with_items(chat, "read", ((m.id, is_read) for m, is_read, _ in arrivals))
    return with_items(chat, "reactions", ((m.id, r) for m, _, r in arrivals if r))


def with_read(chat: Chat, message_ids: Iterable[str], is_read: bool) -> Chat:
    """Mark messages read or unread; ids already so, or not there, change nothing."""
    return with_items(chat, "read", ((i, is_read) for i in message_ids if i in chat.read))


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
    return with_items(chat, "reactions", [(message_id, tuple(current.items()))])


# --- counts (baselines, badges) ---------------------------------------------------------------


def unread_ids(chat: Chat) -> list[str]:
    """Unread and still there: a message its sender deleted no longer asks to be read."""
    messages = chat.messages
    return [i for i, is_read in chat.read.items() if not is_read and messages[i].gone_at is None]


def unread_in(chat: Chat, conversation_id: str) -> list[str]:
    """What opening the chat reads: its unread messages, in delivery order."""
    return [i for i in unread_ids(chat) if chat.messages[i].conversation_id == conversation_id]


def unread_count(chat: Chat) -> int:
    return len(unread_ids(chat))


def unread_conversation_count(chat: Chat) -> int:
    return len({chat.messages[i].conversation_id for i in unread_ids(chat)})


def unread_with(flag: str) -> Callable[[Chat], int]:
    """The count of unread messages with `flag` set (the original's definitions)."""
    return lambda chat: sum(1 for i in unread_ids(chat) if getattr(chat.messages[i], flag))


mention_count = unread_with("mentions_me")
urgent_count = unread_with("is_urgent")


missed_call_count = counting("calls", "missed")
total_message_count = counting("messages")
