"""MicroGram's registration with the core: scenario events, baselines, evaluation tables.

Scenario events (SentinelBench format):
- `preload_posts {post_ids, story_ids, message_ids, activity_ids}` — the app as the task starts
  (each list may be `["*"]`; `message_ids` are DM thread ids, each thread with its messages and
  their catalog read flags). Optional `liked_post_ids`, `saved_post_ids`, `followed_user_ids`,
  `viewed_story_ids`. Baselines are measured right after it.
- `new_post {post_id}`, `new_story {story_id}`, `new_message {message_id}` (a whole DM thread),
  `new_activity {activity_id}` — one item arriving now.
"""

from __future__ import annotations

import sqlite3
from collections.abc import Mapping
from dataclasses import replace
from types import MappingProxyType

from pydantic import Field

from apps.kit.frozen import with_items
from apps.kit.legacy_tables import Table
from apps.microgram import catalog as records
from apps.microgram import state as gram_state
from apps.microgram.actions import ACTIONS
from apps.microgram.bench import sample_pages
from apps.microgram.state import ENVIRONMENT, Gram, PostState, with_post_state
from events.registry import Environment, EventType, ImplicitAction, LoggedEvent, Measure, timeless
from events.schemas import Payload

# Counted right after the preload, by the core (the original's names: baseline_<name>).
BASELINES: Mapping[str, Measure] = MappingProxyType(
    {
        name: timeless(count)
        for name, count in {
            "liked_count": gram_state.liked_count,
            "saved_count": gram_state.saved_count,
            "comment_count": gram_state.comment_count,
            "followed_count": gram_state.followed_count,
            "story_viewed_count": gram_state.story_viewed_count,
            "post_count": gram_state.post_count,
            "story_count": gram_state.story_count,
            "activity_count": gram_state.activity_count,
        }.items()
    }
)


# --- delivering catalog items -------------------------------------------------------------------
# An id already present is the same item delivered twice: left as it is (the original appended a
# second copy and reset its read flags). Ids missing from the catalog are skipped; scenario
# validation reports them to the author before a run starts.


def _fresh(present: Mapping[str, object], ids: list[str]) -> list[str]:
    return [i for i in dict.fromkeys(ids) if i not in present]


def arrival(gram: Gram, name: str, item_id: str, at: float, preloaded: bool) -> float:
    """When the item appeared: now, or (preloaded) its catalog age before the preload."""
    if not preloaded:
        return at
    record = records.table(gram.catalog, name).get(item_id) or {}
    return at - records.preload_age(gram.catalog, name, record)


def deliver_posts(gram: Gram, ids: list[str], at: float, preloaded: bool) -> Gram:
    posts = [
        records.catalog_post(gram.catalog, i, posted_at=arrival(gram, "posts", i, at, preloaded))
        for i in _fresh(gram.posts, ids)
    ]
    posts = [p for p in posts if p is not None]
    gram = with_items(gram, "posts", ((p.id, p) for p in posts))
    return with_items(gram, "post_states", ((p.id, PostState()) for p in posts))


def deliver_stories(gram: Gram, ids: list[str], at: float, preloaded: bool) -> Gram:
    stories = [
        records.catalog_story(gram.catalog, i, posted_at=arrival(gram, "stories", i, at, preloaded))
        for i in _fresh(gram.stories, ids)
    ]
    return with_items(gram, "stories", ((s.id, s) for s in stories if s is not None))


def deliver_conversations(gram: Gram, ids: list[str], at: float, preloaded: bool) -> Gram:
    """Each thread with all of its messages, their read flags from the catalog."""
    for conversation_id in _fresh(gram.conversations, ids):
        conversation = records.catalog_conversation(
            gram.catalog,
            conversation_id,
            arrived_at=arrival(gram, "messages", conversation_id, at, preloaded),
        )
        if conversation is None:
            continue
        gram = with_items(gram, "conversations", [(conversation_id, conversation)])
        reads = records.initial_reads(gram.catalog, conversation_id)
        gram = with_items(gram, "read_messages", reads.items())
    return gram


def deliver_activity(gram: Gram, ids: list[str], at: float, preloaded: bool) -> Gram:
    items = [
        records.catalog_activity(
            gram.catalog, i, posted_at=arrival(gram, "activity", i, at, preloaded)
        )
        for i in _fresh(gram.activity, ids)
    ]
    items = [a for a in items if a is not None]
    gram = with_items(gram, "activity", ((a.id, a) for a in items))
    # Preloaded items keep the catalog's read flag (older ones were seen before the task);
    # what arrives later is unread.
    read = {a.id for a in items if preloaded and records.activity_read(gram.catalog, a.id)}
    return replace(gram, read_activity=gram.read_activity | read) if read else gram


# --- scenario events ------------------------------------------------------------------------------


class PreloadPosts(Payload):
    post_ids: list[str] = Field(default_factory=list, description='["*"] = every post')
    story_ids: list[str] = Field(default_factory=list, description='["*"] = every story')
    message_ids: list[str] = Field(default_factory=list, description='DM thread ids; ["*"] = all')
    activity_ids: list[str] = Field(default_factory=list, description='["*"] = all activity')
    liked_post_ids: list[str] = Field(default_factory=list, description="already liked")
    saved_post_ids: list[str] = Field(default_factory=list, description="already saved")
    followed_user_ids: list[str] = Field(default_factory=list, description="already followed")
    viewed_story_ids: list[str] = Field(default_factory=list, description="already watched")


def reduce_preload_posts(gram: Gram, event: LoggedEvent) -> Gram:
    """The starting app. Likes, saves and views apply only to items that were loaded."""
    p, at, catalog = event.payload, event.at, gram.catalog

    def ids(field: str, table: str) -> list[str]:
        return catalog.expand(ENVIRONMENT, table, p.get(field) or [])

    gram = deliver_posts(gram, ids("post_ids", "posts"), at, preloaded=True)
    gram = deliver_stories(gram, ids("story_ids", "stories"), at, preloaded=True)
    gram = deliver_conversations(gram, ids("message_ids", "messages"), at, preloaded=True)
    gram = deliver_activity(gram, ids("activity_ids", "activity"), at, preloaded=True)
    for post_id in p.get("liked_post_ids") or ():
        gram = with_post_state(gram, post_id, is_liked=True)
    for post_id in p.get("saved_post_ids") or ():
        gram = with_post_state(gram, post_id, is_saved=True)
    viewed = {s for s in p.get("viewed_story_ids") or () if s in gram.stories}
    followed = tuple(dict.fromkeys((*gram.followed, *(p.get("followed_user_ids") or ()))))
    return replace(gram, viewed_stories=gram.viewed_stories | viewed, followed=followed)


class NewPost(Payload):
    post_id: str = Field(description="catalog post id")


class NewStory(Payload):
    story_id: str = Field(description="catalog story id")


class NewMessage(Payload):
    message_id: str = Field(description="catalog DM thread id (the original's name)")


class NewActivity(Payload):
    activity_id: str = Field(description="catalog activity id")


def reduce_new_post(gram: Gram, event: LoggedEvent) -> Gram:
    """A post appears at the top of the feed."""
    return deliver_posts(gram, [event.payload["post_id"]], event.at, preloaded=False)


def reduce_new_story(gram: Gram, event: LoggedEvent) -> Gram:
    """A story appears in the story bar, not yet watched."""
    return deliver_stories(gram, [event.payload["story_id"]], event.at, preloaded=False)


def reduce_new_message(gram: Gram, event: LoggedEvent) -> Gram:
    """A whole DM thread arrives, its messages' read flags from the catalog."""
    return deliver_conversations(gram, [event.payload["message_id"]], event.at, preloaded=False)


def reduce_new_activity(gram: Gram, event: LoggedEvent) -> Gram:
    return deliver_activity(gram, [event.payload["activity_id"]], event.at, preloaded=False)


EVENT_TYPES: Mapping[str, EventType] = MappingProxyType(
    {
        "preload_posts": EventType(
            schema=PreloadPosts,
            reduce=reduce_preload_posts,
            help="The app at the start: feed posts, stories, DM threads, activity.",
            catalog_refs={
                "post_ids": "posts",
                "story_ids": "stories",
                "message_ids": "messages",
                "activity_ids": "activity",
            },
            preload=True,
        ),
        "new_post": EventType(
            NewPost,
            reduce_new_post,
            help="A post appears in the feed (with its comments).",
            catalog_refs={"post_id": "posts"},
        ),
        "new_story": EventType(
            NewStory,
            reduce_new_story,
            help="A story appears in the story bar.",
            catalog_refs={"story_id": "stories"},
        ),
        "new_message": EventType(
            NewMessage,
            reduce_new_message,
            help="A DM thread arrives.",
            catalog_refs={"message_id": "messages"},
        ),
        "new_activity": EventType(
            NewActivity,
            reduce_new_activity,
            help="An activity item (like, follow, comment, mention) arrives, unread.",
            catalog_refs={"activity_id": "activity"},
        ),
    }
)


# --- evaluation tables (the original's names and columns, so eval_sql runs unchanged) -----------

POSTS = Table(
    "posts",
    (
        "id TEXT PRIMARY KEY",
        "authorId TEXT",
        "caption TEXT",
        "likes INTEGER",
        "isTargetPost INTEGER",
    ),
)
POST_STATES = Table(
    "post_states",
    ("post_id TEXT PRIMARY KEY", "isLiked INTEGER", "isSaved INTEGER", "isViewed INTEGER"),
)
COMMENTS = Table(
    "comments",
    ("id TEXT", "post_id TEXT", "authorId TEXT", "text TEXT", "likes INTEGER"),
)
STORIES = Table("stories", ("id TEXT PRIMARY KEY", "authorId TEXT", "mediaType TEXT"))
STORY_STATES = Table("story_states", ("story_id TEXT PRIMARY KEY", "isViewed INTEGER"))
MESSAGES = Table("messages", ("id TEXT PRIMARY KEY", "data TEXT"))
MESSAGE_STATES = Table("message_states", ("message_id TEXT PRIMARY KEY", "isRead INTEGER"))
SENT_MESSAGES = Table("sent_messages", ("id TEXT PRIMARY KEY", "conversation_id TEXT", "text TEXT"))
ACTIVITY = Table("activity", ("id TEXT PRIMARY KEY", "type TEXT", "actorId TEXT"))
ACTIVITY_STATES = Table("activity_states", ("activity_id TEXT PRIMARY KEY", "isRead INTEGER"))
FOLLOWED_USERS = Table("followed_users", ("user_id TEXT PRIMARY KEY",))
USER_CREATED_COMMENTS = Table(
    "user_created_comments", ("id TEXT PRIMARY KEY", "post_id TEXT", "text TEXT")
)


def materialize(gram: Gram, now: float, conn: sqlite3.Connection) -> None:
    """Write the tables. Nothing here moves between events: `now` is unused.

    `comments` holds every comment under the posts in the feed, as the post shows them: the
    catalog's and the self user's (also in the original's `user_created_comments`, whose
    `post_id` is filled here — the original left it NULL). DMs the
    self user sends go to `sent_messages`, never into `messages.data`, so writing a keyword
    cannot satisfy a keyword watch."""
    g = gram
    POSTS.write(
        conn,
        (
            (p.id, p.author.id, p.caption, gram_state.likes_now(g, p.id), p.is_target)
            for p in g.posts.values()
        ),
    )
    POST_STATES.write(
        conn, ((i, s.is_liked, s.is_saved, s.is_viewed) for i, s in g.post_states.items())
    )
    COMMENTS.write(
        conn,
        (
            (c.id, p.id, c.author.id, c.text, c.likes)
            for p in g.posts.values()
            for c in gram_state.comments_of(g, p.id)
        ),
    )
    STORIES.write(conn, ((s.id, s.author.id, s.media_type) for s in g.stories.values()))
    STORY_STATES.write(conn, ((i, i in g.viewed_stories) for i in g.stories))
    MESSAGES.write(conn, ((c.id, c.data) for c in g.conversations.values()))
    MESSAGE_STATES.write(conn, g.read_messages.items())
    SENT_MESSAGES.write(conn, ((m.id, m.conversation_id, m.text) for m in g.sent))
    ACTIVITY.write(conn, ((a.id, a.type, a.actor.id) for a in g.activity.values()))
    ACTIVITY_STATES.write(conn, ((i, i in g.read_activity) for i in g.activity))
    FOLLOWED_USERS.write(conn, ((u,) for u in g.followed))
    USER_CREATED_COMMENTS.write(conn, ((c.id, c.post_id, c.text) for c in g.user_comments))


def empty_gram(catalog) -> Gram:
    return Gram(catalog=catalog, me=records.self_person(catalog))


def _opens_unviewed_post(gram: Gram, post_id: str) -> bool:
    state = gram.post_states.get(post_id)
    return state is not None and not state.is_viewed


def _opens_unviewed_story(gram: Gram, story_id: str) -> bool:
    return story_id in gram.stories and story_id not in gram.viewed_stories


def _opens_unread_thread(gram: Gram, conversation_id: str) -> bool:
    return gram_state.unread_in(gram, conversation_id) > 0


MICROGRAM = Environment(
    name=ENVIRONMENT,
    title="MicroGram",
    initial_state=empty_gram,
    event_types=EVENT_TYPES,
    actions=ACTIONS,
    baselines=BASELINES,
    materialize=materialize,
    urlconf="apps.microgram.urls",
    implicit_actions=(
        # Opening a post (its comments), a story or a DM thread is what views / reads it.
        ImplicitAction(
            page="post",
            param="post_id",
            action="view_post",
            payload=lambda post_id: {"post_id": post_id},
            applies=_opens_unviewed_post,
        ),
        ImplicitAction(
            page="story",
            param="story_id",
            action="view_story",
            payload=lambda story_id: {"story_id": story_id},
            applies=_opens_unviewed_story,
        ),
        ImplicitAction(
            page="thread",
            param="conversation_id",
            action="read_conversation",
            payload=lambda conversation_id: {"conversation_id": conversation_id},
            applies=_opens_unread_thread,
        ),
    ),
    sample_pages=sample_pages,
)
