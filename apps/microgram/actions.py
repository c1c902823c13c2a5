"""What an agent can do on MicroGram: `Action(schema, decide, reduce, page)` per action name.

`decide(gram, payload)` checks the request against the current state and returns the payload to
log (with any id it generated, so replay is deterministic). `reduce` applies a logged action; it
trusts the log and never raises (an id that is gone changes nothing).

The original toggled likes, saves and follows; here each has a set and an unset action, so a
repeated request cannot undo itself (the like count still moves ±1 with the like). Sending a DM
was client-only in the original and is logged here; so is reading activity.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import replace
from types import MappingProxyType
from urllib.parse import quote

from pydantic import Field

from apps.kit import feeds
from apps.kit.deciding import found, new_id
from apps.kit.feeds import ConversationId
from apps.kit.fields import ItemId, Text
from apps.kit.social import PostId, post_actions
from apps.kit.state import with_items
from apps.microgram.catalog import person
from apps.microgram.state import (
    Conversation,
    Gram,
    SentMessage,
    UserComment,
    known_people,
    unread_in,
)
from events.registry import Action, ActionRejected, LoggedEvent, PageStep
from events.schemas import Payload

WHERE = "on MicroGram"  # ends the 404 for an id that is not (yet) on MicroGram


class StoryId(Payload):
    story_id: ItemId = Field(description="id of a story in the story bar")


class SendMessage(ConversationId):
    text: Text = Field(description="the message")


class SharePost(PostId):
    conversation_id: ItemId = Field(description="the DM thread to send it to")
    text: Text = Field("", description="an optional note")


class UserId(Payload):
    user_id: ItemId = Field(description="id of a MicroGram member")


class ActivityId(Payload):
    activity_id: ItemId = Field(description="id of an activity item")


class Nothing(Payload):
    pass


# --- posts -----------------------------------------------------------------------------------


def reduce_comment(gram: Gram, event: LoggedEvent) -> Gram:
    p = event.payload
    if p["post_id"] not in gram.posts:
        return gram
    comment = UserComment(p["id"], p["post_id"], p["text"], event.at)
    return replace(gram, user_comments=(*gram.user_comments, comment))


# --- stories, DMs, activity ------------------------------------------------------------------


def reduce_view_story(gram: Gram, event: LoggedEvent) -> Gram:
    story_id = event.payload["story_id"]
    if story_id not in gram.stories or story_id in gram.viewed_stories:
        return gram
    return replace(gram, viewed_stories=gram.viewed_stories | {story_id})


def reduce_read_conversation(gram: Gram, event: LoggedEvent) -> Gram:
    """Every message of the thread is read."""
    conversation = gram.conversations.get(event.payload["conversation_id"])
    if conversation is None or not unread_in(gram, conversation.id):
        return gram
    return with_items(gram, "read_messages", ((m.id, True) for m in conversation.messages))


def sent(gram: Gram, event: LoggedEvent, post_id: str | None = None) -> Gram:
    """The self user's message (or shared post) joins the thread."""
    p = event.payload
    message = SentMessage(p["id"], p["conversation_id"], p["text"], event.at, post_id)
    return replace(gram, sent=(*gram.sent, message))


def reduce_send(gram: Gram, event: LoggedEvent) -> Gram:
    """Writing in a thread means having it open, so it is read."""
    if event.payload["conversation_id"] not in gram.conversations:
        return gram
    return sent(reduce_read_conversation(gram, event), event)


def decide_share(gram: Gram, payload: dict) -> dict:
    found(gram.posts, payload["post_id"], "post", WHERE)
    found(gram.conversations, payload["conversation_id"], "conversation", WHERE)
    return {**payload, "text": str(payload.get("text") or "").strip(), "id": new_id("user-dm")}


def reduce_share(gram: Gram, event: LoggedEvent) -> Gram:
    """The post goes into the thread as a message from the self user (with the note, if any)."""
    p = event.payload
    if p["conversation_id"] not in gram.conversations or p["post_id"] not in gram.posts:
        return gram
    return sent(gram, event, p["post_id"])


def decide_start(gram: Gram, payload: dict) -> dict:
    """The thread with that person, else a new empty one — only with someone the self user
    follows (the original's New message dialog refused anyone else)."""
    user_id = payload["user_id"]
    existing_thread = feeds.thread_with(gram, user_id)
    if existing_thread is None:
        if user_id not in known_people(gram) or user_id == gram.me.id:
            raise ActionRejected(f"no member {user_id!r} to message on MicroGram", status=404)
        if user_id not in gram.followed:
            raise ActionRejected("you can only start a conversation with someone you follow")
    return {**payload, "conversation_id": existing_thread or new_id("user-thread")}


def new_thread(gram: Gram, event: LoggedEvent) -> Conversation:
    """An empty thread with the person, its `data` as the original stored a new one."""
    p = event.payload
    other = person(gram.catalog, p["user_id"])
    return Conversation(
        id=p["conversation_id"],
        other=other,
        messages=(),
        last_message="",
        data=json.dumps(
            {"id": p["conversation_id"], "participantIds": [gram.me.id, other.id], "messages": []}
        ),
        arrived_at=event.at,
        order=len(gram.conversations),
    )


def reduce_read_activity(gram: Gram, event: LoggedEvent) -> Gram:
    activity_id = event.payload["activity_id"]
    if gram.read_activity.get(activity_id) is not False:  # not there, or read already
        return gram
    return with_items(gram, "read_activity", [(activity_id, True)])


def reduce_read_all_activity(gram: Gram, event: LoggedEvent) -> Gram:
    return replace(gram, read_activity=MappingProxyType(dict.fromkeys(gram.activity, True)))


# --- people ------------------------------------------------------------------------------------


def decide_follow(gram: Gram, payload: dict) -> dict:
    user_id = payload["user_id"]
    if user_id not in known_people(gram):
        raise ActionRejected(f"no member {user_id!r} {WHERE}", status=404)
    if user_id == gram.me.id:
        raise ActionRejected("you cannot follow yourself")
    return payload


def reduce_follow(gram: Gram, event: LoggedEvent) -> Gram:
    user_id = event.payload["user_id"]
    if user_id in gram.followed:
        return gram
    return replace(gram, followed=(*gram.followed, user_id))


def reduce_unfollow(gram: Gram, event: LoggedEvent) -> Gram:
    user_id = event.payload["user_id"]
    return replace(gram, followed=tuple(u for u in gram.followed if u != user_id))


# --- where a person does it (Action.page) --------------------------------------------------------
# Forms and buttons are marked `data-action="<action>"` in the templates; the generic tests carry
# out every scenario's solution through them (tests/environments/).


post_page = feeds.post_page("p/", WHERE)
thread_page = feeds.thread_page(lambda thread_id: f"direct/t/{quote(thread_id)}/", "text", WHERE)
profile_page = feeds.profile_page("profile/")


def story_page(gram: Gram, payload: dict) -> PageStep:
    found(gram.stories, payload["story_id"], "story", WHERE)
    return PageStep(f"stories/{quote(payload['story_id'])}/", None)


def share_page(gram: Gram, payload: dict) -> PageStep:
    found(gram.posts, payload["post_id"], "post", WHERE)
    form = {"conversation_id": payload["conversation_id"], "text": payload.get("text", "")}
    return PageStep(f"p/{quote(payload['post_id'])}/", form)


def activity_page(gram: Gram, payload: dict) -> PageStep:
    form = {"activity_id": payload["activity_id"]} if "activity_id" in payload else {}
    return PageStep("activity/", form)


on_post = feeds.item_action(PostId, "posts", "post", WHERE)
on_story = feeds.item_action(StoryId, "stories", "story", WHERE)
on_thread = feeds.item_action(ConversationId, "conversations", "conversation", WHERE)
on_activity = feeds.item_action(ActivityId, "activity", "activity item", WHERE)


ACTIONS: Mapping[str, Action] = MappingProxyType(
    {
        **post_actions(WHERE, feeds.liking, reduce_comment, post_page),
        "save_post": on_post(
            feeds.post_flag(is_saved=True),
            "Save a post (it shows under Saved on your profile).",
            post_page,
        ),
        "unsave_post": on_post(
            feeds.post_flag(is_saved=False), "Remove a post from Saved.", post_page
        ),
        "view_post": on_post(
            feeds.post_flag(is_viewed=True),
            "Open a post with its comments (what opening it does).",
            feeds.post_page("p/", WHERE, form=False),
        ),
        "view_story": on_story(
            reduce_view_story, "Watch a story (its ring turns grey).", story_page
        ),
        "read_conversation": on_thread(
            reduce_read_conversation, "Open a DM thread; this marks its messages read.", thread_page
        ),
        "send_message": Action(
            SendMessage,
            feeds.sending("text", "user-dm", WHERE),
            reduce_send,
            help="Send a message in a DM thread.",
            page=thread_page,
        ),
        "share_post": Action(
            SharePost,
            decide_share,
            reduce_share,
            help="Send a post to a DM thread, with an optional note.",
            page=share_page,
        ),
        "start_conversation": Action(
            UserId,
            decide_start,
            feeds.starting(new_thread),
            help="Open the DM thread with a person you follow (a new one if there is none).",
            page=profile_page,
        ),
        "follow_user": Action(
            UserId, decide_follow, reduce_follow, help="Follow a member.", page=profile_page
        ),
        "unfollow_user": Action(
            UserId,
            decide_follow,
            reduce_unfollow,
            help="Stop following a member.",
            page=profile_page,
        ),
        "mark_activity_read": on_activity(
            reduce_read_activity,
            "Mark one activity item read (what clicking it does).",
            activity_page,
        ),
        "mark_all_activity_read": Action(
            Nothing,
            lambda gram, payload: payload,
            reduce_read_all_activity,
            help="Mark every activity item read.",
            page=activity_page,
        ),
    }
)
