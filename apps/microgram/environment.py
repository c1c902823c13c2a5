"""MicroGram's registration with the core: scenario events, baselines, evaluation tables.

Scenario events (SentinelBench format):
- `preload_posts {post_ids, story_ids, message_ids, activity_ids}` — the app as the task starts
  (each list may be `["*"]`; `message_ids` are DM thread ids, each thread with its messages and
  their catalog read flags). Optional `liked_post_ids`, `saved_post_ids`, `followed_user_ids`,
  `viewed_story_ids`. Baselines are measured right after it.
- `new_post {post_id}`, `new_story {story_id}`, `new_message {message_id}` (a whole DM thread),
  `new_activity {activity_id}` — one item arriving now.
- `expire_story {story_id}` — a story expires now (apps.kit.retractions): it leaves the tray.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import replace
from typing import NamedTuple

from pydantic import Field

from apps.kit.arrivals import Delivery, arrival, event_types, preload
from apps.kit.counts import ShownCount, untimed
from apps.kit.environments import declare
from apps.kit.feeds import opening, posts_table
from apps.kit.retractions import retraction, still_there, window
from apps.kit.social import Comment
from apps.kit.state import with_changed, with_items
from apps.kit.tables import KEY, VALUE, Keyed, Table, item_states, named, tables
from apps.microgram import catalog as records
from apps.microgram import state as gram_state
from apps.microgram.state import ENVIRONMENT, Gram, PostState, comments_of, unread_in
from events.registry import counted
from events.schemas import Payload

# Counted right after the preload, by the core (the original's names: baseline_<name>).
BASELINES = counted(
    {
        "liked_count": gram_state.liked_count,
        "saved_count": gram_state.saved_count,
        "comment_count": gram_state.comment_count,
        "followed_count": gram_state.followed_count,
        "story_viewed_count": gram_state.story_viewed_count,
        "post_count": gram_state.post_count,
        "story_count": gram_state.story_count,
        "activity_count": gram_state.activity_count,
    }
)


# --- delivering catalog items (apps.kit.arrivals: an id already present is left as it is; the
# original appended a second copy and reset its read flags) ---------------------------------------

deliver_posts = Delivery("posts", records.catalog_post, states="post_states", fresh=PostState)
deliver_stories = Delivery("stories", records.catalog_story)
deliver_activity = Delivery("activity", records.catalog_activity, states="read_activity")
deliver_thread_records = Delivery("conversations", records.catalog_conversation)


def deliver_threads(gram: Gram, ids: Iterable[str], at: float, *, preloaded: bool) -> Gram:
    """Each thread with all of its messages, their read flags (message id → read) from the
    catalog, whenever the thread arrives."""
    arriving = [i for i in dict.fromkeys(ids) if i not in gram.conversations]
    gram = deliver_thread_records(gram, arriving, at, preloaded=preloaded)
    reads = (
        read
        for conversation_id in arriving
        if conversation_id in gram.conversations
        for read in records.initial_reads(gram.catalog, conversation_id).items()
    )
    return with_items(gram, "read_messages", reads)


# --- scenario events ------------------------------------------------------------------------------


class AlreadyDone(Payload):
    """What the self user did before the task started, to items the preload loads."""

    liked_post_ids: list[str] = Field(default_factory=list, description="already liked")
    saved_post_ids: list[str] = Field(default_factory=list, description="already saved")
    followed_user_ids: list[str] = Field(default_factory=list, description="already followed")
    viewed_story_ids: list[str] = Field(default_factory=list, description="already watched")


def already_done(gram: Gram, payload: Mapping, at: float) -> Gram:
    """Likes, saves and views apply only to items that were loaded; follows to anyone."""
    for ids, flag in (("liked_post_ids", "is_liked"), ("saved_post_ids", "is_saved")):
        for post_id in payload.get(ids) or ():
            gram = with_changed(gram, "post_states", post_id, **{flag: True})
    viewed = {s for s in payload.get("viewed_story_ids") or () if s in gram.stories}
    followed = tuple(dict.fromkeys((*gram.followed, *(payload.get("followed_user_ids") or ()))))
    return replace(gram, viewed_stories=gram.viewed_stories | viewed, followed=followed)


EVENT_TYPES = event_types(
    preload(
        "preload_posts",
        {
            "post_ids": ("posts", deliver_posts),
            "story_ids": ("stories", deliver_stories),
            "message_ids": ("messages", deliver_threads),
            "activity_ids": ("activity", deliver_activity),
        },
        base=AlreadyDone,
        then=already_done,
        environment=ENVIRONMENT,
        help="The app at the start: feed posts, stories, DM threads, activity.",
    ),
    arrival(
        "new_post",
        "post_id",
        "posts",
        deliver_posts,
        help="A post appears in the feed (with its comments).",
    ),
    arrival(
        "new_story",
        "story_id",
        "stories",
        deliver_stories,
        help="A story appears in the story bar.",
    ),
    retraction(
        "expire_story",
        "story_id",
        "stories",
        "stories",
        help="A story expires: it leaves the story tray (open, it says it is unavailable).",
    ),
    arrival(
        "new_message",
        "message_id",
        "messages",
        deliver_threads,
        help="A DM thread arrives.",
        description="catalog DM thread id (the original's name)",
    ),
    arrival(
        "new_activity",
        "activity_id",
        "activity",
        deliver_activity,
        help="An activity item (like, follow, comment, mention) arrives, unread.",
    ),
)


# --- evaluation tables (the original's names and columns, so eval_sql runs unchanged) -----------
# Nothing here moves between events: `now` is unused.
#
# `comments` holds every comment under the posts in the feed, as the post shows them: the
# catalog's and the self user's (also in the original's `user_created_comments`, whose `post_id`
# is filled here — the original left it NULL). DMs the self user sends go to `sent_messages`,
# never into `messages.data`, so writing a keyword cannot satisfy a keyword watch.


class PostComment(NamedTuple):
    post_id: str
    comment: Comment


def post_comments(gram: Gram, now: float) -> Iterable[PostComment]:
    return (PostComment(p.id, c) for p in gram.posts.values() for c in comments_of(gram, p.id))


def story_states(gram: Gram, now: float) -> Iterable[Keyed]:
    return (Keyed(story_id, story_id in gram.viewed_stories) for story_id in gram.stories)


ID = "id TEXT PRIMARY KEY"  # the key column most tables have, read from the attribute `id`
materialize = tables(
    posts_table(("caption TEXT", "post.caption"), ("isTargetPost INTEGER", "post.is_target")),
    item_states(
        "post",
        {
            "isLiked INTEGER": "is_liked",
            "isSaved INTEGER": "is_saved",
            "isViewed INTEGER": "is_viewed",
        },
    ),
    Table(
        "comments",
        post_comments,
        {
            "id TEXT": "comment.id",
            "post_id TEXT": "post_id",
            "authorId TEXT": "comment.author.id",
            "text TEXT": "comment.text",
            "likes INTEGER": "comment.likes",
        },
    ),
    Table.items(
        "stories",
        {
            "id TEXT PRIMARY KEY": "id",
            "authorId TEXT": "author.id",
            "mediaType TEXT": "media_type",
            **window("posted_at"),
        },
    ),
    Table(
        "story_states", story_states, {"story_id TEXT PRIMARY KEY": KEY, "isViewed INTEGER": VALUE}
    ),
    Table.items("messages", named(ID, "data TEXT"), "conversations"),
    item_states("message", {"isRead INTEGER": VALUE}, "read_messages"),
    Table(
        "sent_messages", lambda gram, now: gram.sent, named(ID, "conversation_id TEXT", "text TEXT")
    ),
    Table.items("activity", {**named(ID, "type TEXT"), "actorId TEXT": "actor.id"}),
    item_states("activity", {"isRead INTEGER": VALUE}, "read_activity"),
    Table(
        "followed_users",
        lambda gram, now: gram.followed,
        {"user_id TEXT PRIMARY KEY": lambda user_id: user_id},
    ),
    Table(
        "user_created_comments",
        lambda gram, now: gram.user_comments,
        named(ID, "post_id TEXT", "text TEXT"),
    ),
)


def _opens_unviewed_post(gram: Gram, post_id: str) -> bool:
    state = gram.post_states.get(post_id)
    return state is not None and not state.is_viewed


def _opens_unwatched_story(gram: Gram, story_id: str) -> bool:
    return still_there(gram.stories, story_id) and story_id not in gram.viewed_stories


def _opens_unread_thread(gram: Gram, conversation_id: str) -> bool:
    return unread_in(gram, conversation_id) > 0


# The numbers shown in more than one place (apps.kit.counts): the sidebar's badges on every page.
SHOWN_COUNTS = (
    ShownCount(
        "unread conversations",
        untimed(gram_state.unread_conversation_count),
        ("{n} Messages", "{n} unread conversations?"),
    ),
    ShownCount(
        "unread notifications",
        untimed(gram_state.unread_activity_count),
        ("Notifications , {n} unread",),
    ),
)


IMPLICIT_ACTIONS = (
    # Opening a post (its comments), a story or a DM thread is what views / reads it.
    opening("post", "post_id", "view_post", _opens_unviewed_post),
    opening("story", "story_id", "view_story", _opens_unwatched_story),
    opening("thread", "conversation_id", "read_conversation", _opens_unread_thread),
)


MICROGRAM = declare(
    __name__,
    title="MicroGram",
    initial_state=lambda catalog: Gram(catalog, me=records.MEMBERS.me(catalog)),
)
