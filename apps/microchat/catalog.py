"""Turning catalog records into state values; reads the original's record shapes and ours.

Tables in `microchat/`: `conversations.jsonl`, `messages.jsonl`, `teams.jsonl`, `calls.jsonl`.
The original spells fields both ways (`sender_id` / `senderId`, `is_read` / `isRead`) and may
store `reactions` and `attachments` as JSON strings; both are read. Ours adds, all optional:
`minutesAgo` (how long before the preload a history message was sent), `replyToId`,
`attachments` [{name, kind: image|file, size, subject}], `reactions` [{reaction, userIds}] and a
meeting's `schedule` {day, start, minutes}, `day` counting working days from the run's start.
"""

from __future__ import annotations

import json
import re
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

from apps.kit.arrivals import Stamp
from apps.kit.feeds import from_catalog
from apps.kit.records import read, reader
from apps.kit.simclock import DAY_S, DAY_START_S
from apps.microchat.state import (
    ENVIRONMENT,
    REACTIONS,
    Attachment,
    Call,
    Chat,
    Conversation,
    ConversationState,
    Message,
    Reactions,
    Team,
)

# The original stored reactions by emoji; ours by name (drawn as icons).
EMOJI_REACTIONS: Mapping[str, str] = {
    "👍": "like",
    "❤️": "heart",
    "❤": "heart",
    "😂": "laugh",
    "😆": "laugh",
    "🎉": "celebrate",
    "😢": "sad",
    "😮": "sad",
    "😡": "angry",
    "😠": "angry",
}
# Upstream preloaded messages are stamped five minutes before the preload.
DEFAULT_MINUTES_AGO = 5.0


def _field(record: Mapping[str, Any], *names: str, default: Any = None) -> Any:
    for name in names:
        if record.get(name) is not None:
            return record[name]
    return default


def _json_list(value: Any) -> list:
    if isinstance(value, str):
        try:
            value = json.loads(value)
        except ValueError:
            return []
    return value if isinstance(value, list) else []


def reaction_name(value: str) -> str:
    return value if value in REACTIONS else EMOJI_REACTIONS.get(value, value)


def catalog_reactions(record: Mapping[str, Any]) -> Reactions:
    reactions: dict[str, tuple[str, ...]] = {}
    for entry in _json_list(record.get("reactions")):
        if not isinstance(entry, dict):
            continue
        name = reaction_name(str(_field(entry, "reaction", "emoji", default="")))
        users = tuple(str(u) for u in _field(entry, "userIds", "user_ids", default=()) or ())
        if name and users:
            reactions[name] = reactions.get(name, ()) + users
    return tuple(reactions.items())


def catalog_attachments(record: Mapping[str, Any]) -> tuple[Attachment, ...]:
    items = []
    for entry in _json_list(record.get("attachments")):
        if not isinstance(entry, dict):
            continue
        image = str(_field(entry, "kind", "type", default="file")).startswith("image")
        items.append(replace(read(Attachment, entry), kind="image" if image else "file"))
    if not items and record.get("hasAttachment"):
        # The original's catalog flags attachments without describing them: show a file row.
        items.append(Attachment(name="Attachment"))
    return tuple(items)


@from_catalog(ENVIRONMENT, "messages")
def catalog_message(
    chat: Chat, message_id: str, record: Mapping[str, Any], stamp: Stamp
) -> tuple[Message, bool, Reactions]:
    """The message as it arrives (a preloaded one `minutesAgo` before the preload), its read
    state (the catalog's, as in the original, for new and preloaded messages alike) and
    reactions."""
    sender_id = str(_field(record, "sender_id", "senderId", default=""))
    attachments = catalog_attachments(record)
    minutes_ago = float(_field(record, "minutesAgo", default=DEFAULT_MINUTES_AGO))
    by_self = sender_id == chat.self_id
    message = read(
        Message,
        record,
        id=message_id,
        conversation_id=str(_field(record, "conversation_id", "conversationId", default="")),
        sender_id=sender_id,
        sender_name=chat.user_name(sender_id, str(_field(record, "senderName", default="Unknown"))),
        sent_at=stamp.at - 60 * minutes_ago if stamp.preloaded else stamp.at,
        has_attachment=bool(record.get("hasAttachment", False)) or bool(attachments),
        attachments=attachments,
        reply_to=_field(record, "replyToId", "reply_to_id"),
        by_self=by_self,
    )
    is_read = bool(_field(record, "is_read", "isRead", default=by_self))
    return message, is_read, catalog_reactions(record)


def _schedule(record: Mapping[str, Any]) -> tuple[int, str, int] | None:
    schedule = record.get("schedule")
    if not isinstance(schedule, dict) or "start" not in schedule:
        return None
    return (int(schedule.get("day", 0)), str(schedule["start"]), int(schedule.get("minutes", 30)))


@from_catalog(ENVIRONMENT, "conversations")
def make_conversation(
    chat: Chat, conversation_id: str, record: Mapping[str, Any], stamp: Stamp
) -> tuple[Conversation, ConversationState]:
    """A conversation of the workspace; a direct chat is named after the other person."""
    participants = tuple(str(p) for p in record.get("participantIds") or ())
    kind = str(record.get("type") or "group")
    name = str(record.get("name") or "")
    if kind == "direct":
        other = next((p for p in participants if p != chat.self_id), None)
        name = chat.user_name(other, name)
    conversation = read(
        Conversation,
        record,
        id=conversation_id,
        type=kind,
        name=name or "Untitled chat",
        participant_ids=participants,
        team_id=_field(record, "teamId", "team_id"),
        schedule=_schedule(record),
    )
    return conversation, read(ConversationState, record)


make_team = reader(ENVIRONMENT, "teams", Team)


_CLOCK = re.compile(r"^(\d{1,2}):(\d{2})$")
_AGO = re.compile(r"^(\d+) (minute|min|hour|day|week)s? ago$")
_AGO_UNIT_S = {"minute": 60, "min": 60, "hour": 3600, "day": DAY_S, "week": 7 * DAY_S}
# The hour a call the catalog logs only by its day is placed at, so the log sorts and reads
# like one: yesterday afternoon, a day earlier mid-afternoon, last week late morning.
_DAY_WORDS = {"Yesterday": (1, 16), "Last week": (7, 11)}


def logged_call_at(text: str, at: float) -> float | None:
    """When a call the catalog logs in words ("08:12", "Yesterday", "2 days ago") took place,
    as a simulated second before `at` (its preload); None for words we cannot place. Calls
    and reactions are then ordered and dated on one clock (the Activity feed mixes them)."""
    text = text.strip()
    if match := _CLOCK.match(text):
        then = int(match[1]) * 3600 + int(match[2]) * 60 - DAY_START_S
        return then if then <= at else then - DAY_S  # a later hour than now: yesterday's
    if match := _AGO.match(text):
        unit = _AGO_UNIT_S[match[2]]
        if unit < DAY_S:
            return at - int(match[1]) * unit
        return int(match[1]) * -unit + 14 * 3600 - DAY_START_S
    if text in _DAY_WORDS:
        days, hour = _DAY_WORDS[text]
        return -days * DAY_S + hour * 3600 - DAY_START_S
    return None


@from_catalog(ENVIRONMENT, "calls")
def make_call(chat: Chat, call_id: str, record: Mapping[str, Any], stamp: Stamp) -> Call:
    """A call of the log: one delivered by a `new_call` event carries its arrival time, one
    preloaded the time the catalog's own words ("2 hours ago") stand for."""
    user_id = _field(record, "userId", "user_id")
    return read(
        Call,
        record,
        id=call_id,
        # The newer original handler names a person's call after the person.
        name=chat.user_name(user_id, str(record.get("name", ""))),
        # The original wrote `callerId`, which its catalog never sets (its UI read `userId`):
        # the column now names the caller whenever the catalog does either way.
        caller_id=_field(record, "callerId", "userId"),
        at=logged_call_at(str(record.get("time") or ""), stamp.at) if stamp.preloaded else stamp.at,
    )
