"""MicroGram as immutable values, and the questions pages and baselines ask of it.

`Gram` is what the reducers build and what every page, baseline and evaluation reads. It is never
mutated: a reducer returns a new `Gram`. Content (a post, a story, a DM thread, an activity item)
is fixed when it arrives; what the user changes about it lives beside it in a `*State` record, as
in the original's `<table>_states` evaluation tables.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

from apps.kit.derived import per_state
from apps.kit.feeds import counting
from apps.kit.records import flag, from_catalog, integer, raw, text_or
from apps.kit.retractions import present
from apps.kit.social import Comment, Picture
from apps.kit.state import EMPTY, CatalogState

ENVIRONMENT = "microgram"


@dataclass(frozen=True)
class Person:
    """Someone as MicroGram shows them (the same name and face in every environment)."""

    id: str
    name: str
    username: str
    bio: str = ""
    website: str = from_catalog(text_or("website"), default="")
    followers: int = from_catalog(integer("followers"), default=0)
    following: int = from_catalog(integer("following"), default=0)
    posts_count: int = from_catalog(integer("postsCount"), default=0)
    verified: bool = from_catalog(flag("isVerified"), default=False)


@dataclass(frozen=True)
class Post:
    id: str
    author: Person
    image: Picture
    caption: str = from_catalog(text_or("caption"))
    location: str = from_catalog(text_or("location"))
    # as delivered; the self user's like is added by `likes_now`
    likes: int = from_catalog(integer("likes"))
    comments: tuple[Comment[Person], ...]  # the catalog's (the `comments` evaluation table)
    is_target: bool = from_catalog(flag("isTargetPost"))
    posted_at: float
    order: int = from_catalog(integer("order"))


@dataclass(frozen=True)
class PostState:
    is_liked: bool = False
    is_saved: bool = False
    is_viewed: bool = False  # the post was opened


@dataclass(frozen=True)
class Story:
    id: str
    author: Person
    image: Picture
    media_type: str = from_catalog(text_or("mediaType", "image"))
    posted_at: float
    order: int = from_catalog(integer("order"))
    gone_at: float | None = None  # expired then: out of the tray (apps.kit.retractions)


@dataclass(frozen=True)
class Message:
    id: str
    sender: Person
    text: str = from_catalog(text_or("text"))
    order: int


@dataclass(frozen=True)
class Conversation:
    """A DM thread with `other`. `data` is the thread as the catalog gives it, as JSON text (the
    original's `messages.data`: keyword evaluations match it with LIKE)."""

    id: str
    other: Person
    messages: tuple[Message, ...]
    last_message: str
    data: str
    arrived_at: float
    order: int = from_catalog(integer("order"))


@dataclass(frozen=True)
class SentMessage:
    """A message the self user wrote in a thread during the run."""

    id: str
    conversation_id: str
    text: str
    at: float
    post_id: str | None = None  # a shared post


@dataclass(frozen=True)
class Activity:
    id: str
    type: str = from_catalog(text_or("type", "mention"))
    actor: Person
    text: str = from_catalog(text_or("text"))
    target_post_id: str | None = from_catalog(raw("targetPostId"))
    posted_at: float
    order: int = from_catalog(integer("order"))


@dataclass(frozen=True)
class UserComment:
    id: str
    post_id: str
    text: str
    at: float


@dataclass(frozen=True)
class Gram(CatalogState):
    # The self user is an input, not state (like the catalog): left out of equality.
    me: Person = field(compare=False, repr=False, default=Person("me", "Me", "me"))
    posts: Mapping[str, Post] = field(default_factory=lambda: EMPTY)
    post_states: Mapping[str, PostState] = field(default_factory=lambda: EMPTY)
    stories: Mapping[str, Story] = field(default_factory=lambda: EMPTY)
    viewed_stories: frozenset[str] = frozenset()
    conversations: Mapping[str, Conversation] = field(default_factory=lambda: EMPTY)
    read_messages: Mapping[str, bool] = field(default_factory=lambda: EMPTY)  # nested id → read
    sent: tuple[SentMessage, ...] = ()
    activity: Mapping[str, Activity] = field(default_factory=lambda: EMPTY)
    read_activity: Mapping[str, bool] = field(default_factory=lambda: EMPTY)  # id → read
    followed: tuple[str, ...] = ()  # user ids, in the order followed
    user_comments: tuple[UserComment, ...] = ()


# --- questions (a post's likes, the thread with someone: apps.kit.feeds) ------------------------
# (The original's card counted the self user's like twice: the server had already added it.)


def comments_of(gram: Gram, post_id: str) -> tuple[Comment[Person], ...]:
    """Every comment under the post: the catalog's, then the self user's (the original showed
    these only until a reload)."""
    own = tuple(
        Comment(c.id, gram.me, c.text, 0, c.at) for c in gram.user_comments if c.post_id == post_id
    )
    return gram.posts[post_id].comments + own


def newest_first(items: Iterable[Any]) -> list[Any]:
    """Newest first (`posted_at`); items of the same moment by the catalog's order, higher
    first (the original's only notion of recency)."""
    return sorted(items, key=lambda x: (-x.posted_at, -x.order))


def unread_in(gram: Gram, conversation_id: str) -> int:
    conversation = gram.conversations.get(conversation_id)
    if conversation is None:
        return 0
    return sum(1 for m in conversation.messages if not gram.read_messages.get(m.id, True))


def is_following(gram: Gram, user_id: str) -> bool:
    return user_id in gram.followed


# --- counts (baselines and badges: the original's definitions) --------------------------------

post_count = counting("posts")


def story_count(gram: Gram) -> int:
    """The stories in the tray: an expired one is no longer counted."""
    return len(present(gram.stories.values()))


activity_count = counting("activity")
liked_count = counting("post_states", is_liked=True)
saved_count = counting("post_states", is_saved=True)
comment_count = counting("user_comments")
followed_count = counting("followed")
story_viewed_count = counting("viewed_stories")


def unread_activity_count(gram: Gram) -> int:
    return sum(1 for read in gram.read_activity.values() if not read)


def unread_conversation_count(gram: Gram) -> int:
    return sum(1 for c in gram.conversations if unread_in(gram, c) > 0)


@per_state()
def known_people(gram: Gram) -> frozenset[str]:
    """Members the app has shown so far: the self user, the people followed and everyone in the
    delivered posts, comments, stories, threads and activity. Anyone else has not "appeared"
    yet, so their profile is a 404 and they are absent from search (like an item whose event
    has not fired)."""
    ids = {gram.me.id, *gram.followed}
    for post in gram.posts.values():
        ids.add(post.author.id)
        ids.update(c.author.id for c in post.comments)
    ids.update(s.author.id for s in gram.stories.values())
    ids.update(c.other.id for c in gram.conversations.values())
    ids.update(a.actor.id for a in gram.activity.values())
    return frozenset(ids)
