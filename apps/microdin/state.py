"""The professional network as immutable values, and the questions pages and baselines ask of it.

`Network` is what the reducers build and what every page, baseline and evaluation reads. It is
never mutated: a reducer returns a new `Network`. Content (a post, a job, a message) is fixed
when it arrives; what the user can change about it lives beside it in a `*State` record, as in
the original's `<table>_states` evaluation tables.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import TypeVar

from apps.kit.feeds import counting
from apps.kit.records import from_catalog, integer, raw, text, text_or
from apps.kit.social import Comment, Picture
from apps.kit.state import EMPTY, CatalogState

ENVIRONMENT = "microdin"
Item = TypeVar("Item")  # a post, a job… (anything stamped with a time and a catalog order)

SECTION_TYPES = ("experience", "education", "skill", "certification", "project", "volunteering")


@dataclass(frozen=True)
class Company:
    id: str
    name: str
    description: str = from_catalog(text_or("description"), default="")
    industry: str = from_catalog(text_or("industry"), default="")


@dataclass(frozen=True)
class Person:
    """Someone as a card shows them: name, headline, company (the same everywhere)."""

    id: str
    name: str
    title: str = ""
    company: Company | None = None
    location: str = ""

    @property
    def headline(self) -> str:
        if self.title and self.company:
            return f"{self.title} at {self.company.name}"
        return self.title or (self.company.name if self.company else "")


@dataclass(frozen=True)
class Post:
    id: str
    author: Person
    content: str = from_catalog(text("content"))
    # as delivered; the user's own like is added by `likes_now`
    likes: int = from_catalog(integer("likes"))
    shares: int = from_catalog(integer("shares"))
    comments: tuple[Comment[Person], ...]
    posted_at: float
    order: int
    image: Picture | None = None  # an image attached to the post


@dataclass(frozen=True)
class PostState:
    is_liked: bool = False
    comments: tuple[Comment[Person], ...] = ()  # written by the self user during the run


@dataclass(frozen=True)
class Connection:
    """A connection request (an invitation) from `person`."""

    id: str
    person: Person
    mutual: int = from_catalog(integer("mutualConnections"))
    received_at: float
    order: int


@dataclass(frozen=True)
class ConnectionState:
    # pending | accepted | ignored: as the catalog says, else pending
    status: str = from_catalog(text_or("status", "pending"), default="pending")


@dataclass(frozen=True)
class Conversation:
    """A one-to-one thread between the self user and `other`."""

    id: str
    other: Person
    order: int


@dataclass(frozen=True)
class Message:
    id: str
    conversation_id: str
    sender: Person
    content: str = from_catalog(lambda r: str(r.get("text", r.get("content", ""))))
    sent_at: float
    order: int  # position in its conversation


@dataclass(frozen=True)
class ReadState:
    """A message's or a notification's own state: whether the user has read it."""

    is_read: bool = False


@dataclass(frozen=True)
class Notification:
    id: str
    type: str
    actor: Person
    content: str
    at: float
    order: int
    target_post_id: str | None = from_catalog(raw("targetPostId"), default=None)
    # a job notification's employer: its logo, not a person's face
    company: str = from_catalog(text_or("company"), default="")


@dataclass(frozen=True)
class Job:
    id: str
    title: str = from_catalog(text("title"))
    company: Company
    location: str = from_catalog(text("location"))
    type: str = from_catalog(text_or("type", "full-time"))
    description: str = from_catalog(text("description"))
    requirements: tuple[str, ...] = from_catalog(
        lambda r: tuple(str(line) for line in r.get("requirements") or ())
    )
    # the catalog's count, for a posting that was up before the run
    applicants: int = from_catalog(integer("applicants"))
    posted_at: float
    order: int
    # Posted while the run plays (minutes ago): it cannot have its catalogued applicants yet,
    # so it reads as LinkedIn's fresh postings do, "Be among the first 25 applicants".
    posted_during_run: bool = False
    # Closed to applications then (apps.kit.retractions): the posting stays, without Apply.
    gone_at: float | None = None

    @property
    def applicants_shown(self) -> int | None:
        """The applicant count the posting shows; None for a fresh one (no count yet)."""
        return None if self.posted_during_run else self.applicants


@dataclass(frozen=True)
class JobState:
    is_applied: bool = False


@dataclass(frozen=True)
class ProfileSection:
    """A section the self user added to their profile (experience, education, skill…)."""

    id: str
    type: str
    title: str
    subtitle: str = ""
    content: str = ""


@dataclass(frozen=True)
class ProfileStats:
    """The self user's numbers as the task starts (the preload may set them)."""

    profile_views: int = 0
    page_visitors: int = 0
    connections: int = 0
    connected_ids: tuple[str, ...] = ()  # people the self user is connected to already


@dataclass(frozen=True)
class Network(CatalogState):
    # The self user is an input, not state (like the catalog): left out of equality.
    me: Person = field(compare=False, repr=False, default=Person("me", "Me"))
    posts: Mapping[str, Post] = field(default_factory=lambda: EMPTY)
    post_states: Mapping[str, PostState] = field(default_factory=lambda: EMPTY)
    connections: Mapping[str, Connection] = field(default_factory=lambda: EMPTY)
    connection_states: Mapping[str, ConnectionState] = field(default_factory=lambda: EMPTY)
    conversations: Mapping[str, Conversation] = field(default_factory=lambda: EMPTY)
    messages: Mapping[str, Message] = field(default_factory=lambda: EMPTY)
    message_states: Mapping[str, ReadState] = field(default_factory=lambda: EMPTY)
    notifications: Mapping[str, Notification] = field(default_factory=lambda: EMPTY)
    notification_states: Mapping[str, ReadState] = field(default_factory=lambda: EMPTY)
    jobs: Mapping[str, Job] = field(default_factory=lambda: EMPTY)
    job_states: Mapping[str, JobState] = field(default_factory=lambda: EMPTY)
    stats: ProfileStats = ProfileStats()
    sections: tuple[ProfileSection, ...] = ()


# --- questions (a post's likes, the thread with someone: apps.kit.feeds) -------------------------


def all_comments(network: Network, post_id: str) -> tuple[Comment[Person], ...]:
    return network.posts[post_id].comments + network.post_states[post_id].comments


def status(network: Network, connection_id: str) -> str:
    return network.connection_states[connection_id].status


def conversation_messages(network: Network, conversation_id: str) -> list[Message]:
    return sorted(
        (m for m in network.messages.values() if m.conversation_id == conversation_id),
        key=lambda m: (m.sent_at, m.order),
    )


def unread_messages(network: Network, conversation_id: str) -> list[Message]:
    return [
        m
        for m in network.messages.values()
        if m.conversation_id == conversation_id and not network.message_states[m.id].is_read
    ]


def unread_in(network: Network, conversation_id: str) -> int:
    return len(unread_messages(network, conversation_id))


def newest_first(items: Iterable[Item], stamp: str) -> list[Item]:
    """Newest first (the time `stamp`); equal times keep the catalog order (the original's list
    order)."""
    return sorted(items, key=lambda item: (-getattr(item, stamp), item.order))


def connections_count(network: Network) -> int:
    """Connections shown on the profile: the starting count plus invitations accepted since."""
    return network.stats.connections + accepted_count(network)


# --- counts (baselines and badges: the original's definitions) --------------------------------

post_count = counting("posts")
pending_connection_count = counting("connection_states", status="pending")
unread_message_count = counting("message_states", is_read=False)
unread_notification_count = counting("notification_states", is_read=False)
job_count = counting("jobs")
applied_job_count = counting("job_states", is_applied=True)
accepted_count = counting("connection_states", status="accepted")


def unread_conversation_count(network: Network) -> int:
    unread = {
        network.messages[i].conversation_id
        for i, s in network.message_states.items()
        if not s.is_read
    }
    return len(unread)
