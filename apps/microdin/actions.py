"""What an agent can do on the network: `Action(schema, decide, reduce, page)` per action name.

`decide(network, payload)` checks the request against the current network and returns the
payload to log (with any id it generated, so replay is deterministic). `reduce` applies a logged
action; it trusts the log and never raises (an id that is gone changes nothing).

Likes are set explicitly (like_post / unlike_post) rather than toggled as in the original, so a
repeated request cannot undo itself; the like count moves with them (±1, as in the original).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace
from types import MappingProxyType
from typing import Literal
from urllib.parse import quote

from pydantic import Field

from apps.kit import feeds
from apps.kit.deciding import found, marking, new_id
from apps.kit.feeds import ConversationId
from apps.kit.fields import ItemId, Line, Text
from apps.kit.retractions import is_gone
from apps.kit.social import Comment, post_actions
from apps.kit.state import setting, with_changed, with_items
from apps.microdin import catalog as records
from apps.microdin.query import job_path, thread_path
from apps.microdin.state import (
    SECTION_TYPES,
    Conversation,
    Message,
    Network,
    ProfileSection,
    ReadState,
    status,
    unread_messages,
)
from events.registry import Action, ActionRejected, LoggedEvent, PageStep
from events.schemas import Payload

WHERE = "on this network"  # ends the 404 for an id that is not (yet) on the network


class ConnectionId(Payload):
    connection_id: ItemId = Field(description="id of a connection request")


class SendMessage(ConversationId):
    content: Text = Field(description="the message")


class StartConversation(Payload):
    user_id: ItemId = Field(description="the person to write to")


class NotificationId(Payload):
    notification_id: ItemId = Field(description="id of a notification")


class JobId(Payload):
    job_id: ItemId = Field(description="id of a job posting")


class AddProfileSection(Payload):
    type: Literal[SECTION_TYPES]
    title: Line = ""
    subtitle: Line = ""
    content: Text = ""


# --- posts -----------------------------------------------------------------------------------


def reduce_comment(network: Network, event: LoggedEvent) -> Network:
    """The comment is added under the post, by the self user (not an evaluation column)."""
    post_id = event.payload["post_id"]
    current = network.post_states.get(post_id)
    if current is None:
        return network
    comment = Comment(event.payload["id"], network.me, event.payload["text"], 0, event.at)
    return with_changed(network, "post_states", post_id, comments=(*current.comments, comment))


# --- invitations -----------------------------------------------------------------------------


def decide_answer(network: Network, payload: dict) -> dict:
    """Only a pending invitation can be accepted or ignored."""
    connection = found(network.connections, payload["connection_id"], "connection request", WHERE)
    current = status(network, connection.id)
    if current != "pending":
        raise ActionRejected(
            f"the invitation from {connection.person.name} was already {current}", status=409
        )
    return payload


# --- messaging -------------------------------------------------------------------------------


def reduce_send(network: Network, event: LoggedEvent) -> Network:
    """The message is added to the thread, from the self user, read; the thread is read too
    (writing in it means having it open)."""
    p = event.payload
    if p["conversation_id"] not in network.conversations:
        return network
    network = reduce_open(network, event)
    message = Message(p["id"], p["conversation_id"], network.me, p["content"], event.at, 0)
    network = with_items(network, "messages", [(message.id, message)])
    return with_items(network, "message_states", [(message.id, ReadState(is_read=True))])


def reduce_open(network: Network, event: LoggedEvent) -> Network:
    """Every message of the thread is read."""
    unread = unread_messages(network, event.payload["conversation_id"])
    return with_items(network, "message_states", [(m.id, ReadState(is_read=True)) for m in unread])


def decide_start(network: Network, payload: dict) -> dict:
    """The existing one-to-one thread with the person, else a new empty one."""
    user_id = payload["user_id"]
    found(network.catalog.users, user_id, "member", WHERE)
    if user_id == network.me.id:
        raise ActionRejected("you cannot message yourself")
    existing = feeds.thread_with(network, user_id)
    return {**payload, "conversation_id": existing or new_id("user-conv")}


def new_thread(network: Network, event: LoggedEvent) -> Conversation:
    """An empty thread with the person, listed after the threads there are."""
    person = records.person(network.catalog, event.payload["user_id"])
    return Conversation(event.payload["conversation_id"], person, len(network.conversations))


# --- jobs and profile ------------------------------------------------------------------------


def decide_apply(network: Network, payload: dict) -> dict:
    closed = network.jobs.get(payload["job_id"])
    if is_gone(closed):  # still shown, so said as the posting says it, not as an unknown id
        raise ActionRejected(
            f"{closed.title} at {closed.company.name} is no longer accepting applications", 409
        )
    job = found(network.jobs, payload["job_id"], "job", WHERE)
    if network.job_states[job.id].is_applied:
        raise ActionRejected(f"you already applied to {job.title} at {job.company.name}", 409)
    return payload


def decide_section(network: Network, payload: dict) -> dict:
    title, content = payload.get("title", "").strip(), payload.get("content", "").strip()
    if not title and not content:
        raise ActionRejected("payload field 'title' is empty: a section needs a title or content")
    return {**payload, "title": title, "content": content, "id": new_id("section")}


def reduce_section(network: Network, event: LoggedEvent) -> Network:
    p = event.payload
    section = ProfileSection(p["id"], p["type"], p["title"], p.get("subtitle", ""), p["content"])
    return replace(network, sections=(*network.sections, section))


# --- where a person does it (Action.page) --------------------------------------------------------
# Forms and buttons are marked `data-action="<action>"` in the templates; the generic tests carry
# out every scenario's solution through them (tests/environments/).


def invitations_page(network: Network, payload: dict) -> PageStep:
    found(network.connections, payload["connection_id"], "connection request", WHERE)
    return PageStep("mynetwork/invitations/", {"connection_id": payload["connection_id"]})


thread_page = feeds.thread_page(thread_path, "content", WHERE)


def notifications_page(network: Network, payload: dict) -> PageStep:
    found(network.notifications, payload["notification_id"], "notification", WHERE)
    return PageStep("notifications/", {"notification_id": payload["notification_id"]})


def job_page(network: Network, payload: dict) -> PageStep:
    found(network.jobs, payload["job_id"], "job", WHERE)
    return PageStep(job_path(payload["job_id"]), {})


def section_page(network: Network, payload: dict) -> PageStep:
    form = {k: str(payload.get(k, "")) for k in ("type", "title", "subtitle", "content")}
    return PageStep(f"in/{quote(network.me.id)}/", form)


answers = marking(
    ConnectionId, decide_answer, "connection_states", "connection_id", page=invitations_page
)
on_thread = feeds.item_action(ConversationId, "conversations", "conversation", WHERE)
on_notification = feeds.item_action(NotificationId, "notifications", "notification", WHERE)


ACTIONS: Mapping[str, Action] = MappingProxyType(
    {
        **post_actions(WHERE, feeds.liking, reduce_comment, feeds.post_page("feed/update/", WHERE)),
        "accept_connection": answers(status="accepted", help="Accept a pending invitation."),
        "ignore_connection": answers(
            status="ignored", help="Ignore (reject) a pending invitation."
        ),
        "open_conversation": on_thread(
            reduce_open, "Open a thread; this marks its messages read.", thread_page
        ),
        "send_message": Action(
            SendMessage,
            feeds.sending("content", "user-msg", WHERE),
            reduce_send,
            help="Send a message in a thread.",
            page=thread_page,
        ),
        "start_conversation": Action(
            StartConversation,
            decide_start,
            feeds.starting(new_thread),
            help="Open the thread with a person (a new one if there is none).",
            page=feeds.profile_page("in/"),
        ),
        "mark_notification_read": on_notification(
            setting("notification_states", "notification_id", is_read=True),
            "Mark a notification read (what clicking it does).",
            notifications_page,
        ),
        "apply_job": Action(
            JobId,
            decide_apply,
            setting("job_states", "job_id", is_applied=True),
            help="Apply to a job (there is no withdrawing).",
            page=job_page,
        ),
        "add_profile_section": Action(
            AddProfileSection,
            decide_section,
            reduce_section,
            help="Add a section (experience, education, skill…) to the self user's profile.",
            page=section_page,
        ),
    }
)
