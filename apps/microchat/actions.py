"""What an agent can do in the chat: `Action(schema, decide, reduce, page=…)` per action name.

Favourite, mute and reactions are set explicitly (pin / unpin, react / unreact), not toggled as
in the original: a repeated request or two racing tabs cannot flip them back by accident. A
reaction is the self user's (the original always wrote the literal "user000").
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from types import MappingProxyType
from typing import Literal

from pydantic import Field

from apps.kit.deciding import checking, found, new_id
from apps.kit.fields import ItemId, Text
from apps.kit.state import setting, with_changed, without
from apps.kit.streaming import id_payload
from apps.microchat.query import ChatQuery
from apps.microchat.state import (
    REACTIONS,
    Chat,
    Conversation,
    Message,
    unread_in,
    with_messages,
    with_reaction,
    with_read,
)
from events.registry import Action, ActionRejected, LoggedEvent, PageStep

MAX_MESSAGE_LENGTH = 4000


ConversationId = id_payload("ConversationId", "conversation_id", "id of a conversation")
MessageId = id_payload("MessageId", "message_id", "id of a message that has arrived")


class React(MessageId):
    # Literal of a tuple means one of its items: state.REACTIONS stays the one list.
    reaction: Literal[REACTIONS]


class Send(ConversationId):
    content: Text
    reply_to: ItemId | None = Field(None, description="id of the message this answers")


class Edit(MessageId):
    content: Text


IN_WORKSPACE = ("conversation", "in this workspace")
IN_ANY_CHAT = ("message", "in any chat")


def existing_conversation(chat: Chat, conversation_id: str) -> Conversation:
    return found(chat.conversations, conversation_id, *IN_WORKSPACE)


def existing_message(chat: Chat, message_id: str) -> Message:
    """The message, or a 404: unknown and not-yet-arrived ids look the same."""
    return found(chat.messages, message_id, *IN_ANY_CHAT)


def own_message(chat: Chat, message_id: str) -> Message:
    message = existing_message(chat, message_id)
    if not message.sent_in_run:
        raise ActionRejected(f"message {message_id!r} is not one you sent: only yours can change")
    return message


decide_on_conversation = checking("conversations", "conversation_id", *IN_WORKSPACE)
decide_on_message = checking("messages", "message_id", *IN_ANY_CHAT)


# --- reading --------------------------------------------------------------------------------


def decide_open(chat: Chat, payload: dict) -> dict:
    """Opening marks read what is unread in the chat at that moment (and only that: a message
    arriving while the chat stays open stays unread until it is opened again). Only an
    opening that reads something is an action (the implicit action applies only then)."""
    conversation_id = payload["conversation_id"]
    existing_conversation(chat, conversation_id)
    unread = unread_in(chat, conversation_id)
    if not unread:
        raise ActionRejected(f"conversation {conversation_id!r} has nothing unread to open", 409)
    return {**payload, "message_ids": unread}


def reduce_open(chat: Chat, event: LoggedEvent) -> Chat:
    return with_read(chat, event.payload.get("message_ids", ()), True)


def decide_mark_unread(chat: Chat, payload: dict) -> dict:
    """Teams' "Mark as unread": the newest message someone else sent becomes unread."""
    conversation_id = payload["conversation_id"]
    existing_conversation(chat, conversation_id)
    theirs = [
        i
        for i, m in chat.messages.items()
        if m.conversation_id == conversation_id and not m.by_self
    ]
    if not theirs:
        raise ActionRejected(f"conversation {conversation_id!r} has no message to mark unread")
    newest = max(theirs, key=lambda i: chat.messages[i].sent_at)
    return {**payload, "message_id": newest}


def reduce_mark_unread(chat: Chat, event: LoggedEvent) -> Chat:
    return with_read(chat, [event.payload["message_id"]], False)


# --- reactions ------------------------------------------------------------------------------------


def reacting(on: bool, help: str) -> Action:
    """React, or take the reaction back, from the message's own form."""

    def reduce(chat: Chat, event: LoggedEvent) -> Chat:
        p = event.payload
        return with_reaction(chat, p["message_id"], p["reaction"], chat.self_id, on)

    return Action(React, decide_on_message, reduce, help=help, page=message_form("reaction"))


# --- writing ----------------------------------------------------------------------------------------


def message_text(payload: dict) -> str:
    content = payload["content"].strip()
    if not content:
        raise ActionRejected("payload field 'content' is empty: type a message first")
    if len(content) > MAX_MESSAGE_LENGTH:
        raise ActionRejected(
            f"payload field 'content' is {len(content)} characters; at most {MAX_MESSAGE_LENGTH}"
        )
    return content


def decide_send(chat: Chat, payload: dict) -> dict:
    conversation_id = payload["conversation_id"]
    existing_conversation(chat, conversation_id)
    decided = {
        "conversation_id": conversation_id,
        "content": message_text(payload),
        "id": new_id("sent"),
    }
    reply_to = payload.get("reply_to")
    if reply_to:
        if existing_message(chat, reply_to).conversation_id != conversation_id:
            raise ActionRejected(f"message {reply_to!r} is not in conversation {conversation_id!r}")
        decided["reply_to"] = reply_to
    return decided


def reduce_send(chat: Chat, event: LoggedEvent) -> Chat:
    p = event.payload
    if p["conversation_id"] not in chat.conversations:
        return chat
    sent = Message(
        id=p["id"],
        conversation_id=p["conversation_id"],
        sender_id=chat.self_id,
        sender_name=chat.self_name,
        content=p["content"],
        sent_at=event.at,
        reply_to=p.get("reply_to"),
        by_self=True,
        sent_in_run=True,
    )
    return with_messages(chat, [(sent, True, ())])


def decide_edit(chat: Chat, payload: dict) -> dict:
    own_message(chat, payload["message_id"])
    return {"message_id": payload["message_id"], "content": message_text(payload)}


def reduce_edit(chat: Chat, event: LoggedEvent) -> Chat:
    p = event.payload
    return with_changed(chat, "messages", p["message_id"], content=p["content"], edited=True)


def decide_delete(chat: Chat, payload: dict) -> dict:
    own_message(chat, payload["message_id"])
    return payload


def reduce_delete(chat: Chat, event: LoggedEvent) -> Chat:
    return without(chat, event.payload["message_id"], "messages", "read", "reactions")


# --- where a person does it (Action.page) ------------------------------------------------------------
# Every form carries the id it acts on as a hidden field and is marked `data-action="<action>"`;
# the generic tests carry out each scenario's solution through them (tests/environments/).


def conversation_path(conversation_id: str, **extra: str) -> str:
    return ChatQuery(**extra).with_item("conversation", conversation_id)


def conversation_page(*, opened: bool, form: bool) -> Callable[[Chat, dict], PageStep]:
    """The chat's form in the open chat (`opened`: its header menu) or in the chat list (the
    star of its row); without a `form`, opening the chat is the action (an implicit one)."""

    def page(chat: Chat, payload: dict) -> PageStep:
        conversation_id = existing_conversation(chat, payload["conversation_id"]).id
        path = conversation_path(conversation_id) if opened else ""
        return PageStep(path, {"conversation_id": conversation_id} if form else None)

    return page


open_page = conversation_page(opened=True, form=False)
chat_list_form = conversation_page(opened=False, form=True)
header_form = conversation_page(opened=True, form=True)


def composer(chat: Chat, payload: dict) -> PageStep:
    """The composer of the open chat (replying: opened from the message's Reply button)."""
    conversation_id = payload["conversation_id"]
    existing_conversation(chat, conversation_id)
    path = conversation_path(conversation_id, reply=payload.get("reply_to") or "")
    return PageStep(path, {"content": payload["content"]})


def message_form(*fields: str) -> Callable[[Chat, dict], PageStep]:
    """The message's own form in its chat, with `fields` of the payload."""

    def page(chat: Chat, payload: dict) -> PageStep:
        message = existing_message(chat, payload["message_id"])
        form = {"message_id": payload["message_id"], **{f: str(payload[f]) for f in fields}}
        return PageStep(conversation_path(message.conversation_id), form)

    return page


def conversation_flag(
    page: Callable[[Chat, dict], PageStep], help: str = "", **flag: bool
) -> Action:
    """An action that sets a flag of one chat (favourite, muted): set, not toggled."""
    reduce = setting("conversation_states", "conversation_id", **flag)
    return Action(ConversationId, decide_on_conversation, reduce, help=help, page=page)


ACTIONS: Mapping[str, Action] = MappingProxyType(
    {
        "open_conversation": Action(
            ConversationId,
            decide_open,
            reduce_open,
            help="Open a chat; this marks the messages unread in it at that moment read.",
            page=open_page,
        ),
        "mark_unread": Action(
            ConversationId,
            decide_mark_unread,
            reduce_mark_unread,
            help="Mark a chat unread (its newest message from someone else).",
            page=header_form,
        ),
        "pin": conversation_flag(chat_list_form, "Add a chat to Favorites.", is_pinned=True),
        "unpin": conversation_flag(
            chat_list_form, "Remove a chat from Favorites.", is_pinned=False
        ),
        "mute": conversation_flag(header_form, is_muted=True),
        "unmute": conversation_flag(header_form, is_muted=False),
        "react": reacting(True, f"Add your reaction ({', '.join(REACTIONS)}) to a message."),
        "unreact": reacting(False, "Take your reaction back."),
        "send_message": Action(
            Send,
            decide_send,
            reduce_send,
            help="Send a message in a chat, optionally replying to one of its messages.",
            page=composer,
        ),
        "edit_message": Action(
            Edit,
            decide_edit,
            reduce_edit,
            help="Change a message you sent.",
            page=message_form("content"),
        ),
        "delete_message": Action(
            MessageId,
            decide_delete,
            reduce_delete,
            help="Delete a message you sent.",
            page=message_form(),
        ),
    }
)
