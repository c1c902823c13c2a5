"""MicroDin's registration with the core: scenario events, baselines, evaluation tables.

Scenario events (SentinelBench format):
- `preload_posts {post_ids, connection_ids, conversation_ids, notification_ids, job_ids}` — the
  network as the task starts (each list may be `["*"]`; a conversation comes with all of its
  messages). Optional numbers for the profile: `profile_view_count`, `page_visitor_count`,
  `connections_count`, `initial_connection_ids`. Baselines are measured right after it.
- `new_post {post_id}`, `new_connection {connection_id}`, `new_message {message_id}`,
  `new_notification {notification_id}`, `new_job {job_id}` — one item arriving now (a message
  or notification unread, a job not applied to).
"""

from __future__ import annotations

import sqlite3
from collections.abc import Mapping
from dataclasses import replace
from types import MappingProxyType

from pydantic import Field

from apps.kit.frozen import with_items
from apps.kit.legacy_tables import Table
from apps.microdin import catalog as records
from apps.microdin import state as network_state
from apps.microdin.actions import ACTIONS
from apps.microdin.bench import sample_pages
from apps.microdin.catalog import age
from apps.microdin.state import (
    ENVIRONMENT,
    JobState,
    MessageState,
    Network,
    PostState,
    ProfileStats,
)
from events.registry import Environment, EventType, ImplicitAction, LoggedEvent, Measure, timeless
from events.schemas import Payload

# Counted right after the preload, by the core (the original's names: baseline_<name>).
BASELINES: Mapping[str, Measure] = MappingProxyType(
    {
        name: timeless(count)
        for name, count in {
            "post_count": network_state.post_count,
            "pending_connection_count": network_state.pending_connection_count,
            "unread_message_count": network_state.unread_message_count,
            "unread_conversation_count": network_state.unread_conversation_count,
            "unread_notification_count": network_state.unread_notification_count,
            "job_count": network_state.job_count,
            "applied_job_count": network_state.applied_job_count,
        }.items()
    }
)


# --- delivering catalog items -------------------------------------------------------------------
# An id already present is the same item delivered twice: left as it is (no duplicate, no reset
# of what the user did). Ids missing from the catalog are skipped; scenario validation reports
# them to the author before a run starts.


def _fresh(present: Mapping[str, object], ids: list[str]) -> list[tuple[int, str]]:
    return [(n, i) for n, i in enumerate(dict.fromkeys(ids)) if i not in present]


def deliver_posts(network: Network, ids: list[str], at: float, preloaded: bool) -> Network:
    posts = []
    for n, post_id in _fresh(network.posts, ids):
        record = records.table(network.catalog, "posts").get(post_id) or {}
        post = records.catalog_post(
            network.catalog,
            post_id,
            posted_at=at - age(record) if preloaded else at,
            order=records.record_order(network.catalog, "posts", post_id, n),
        )
        if post is not None:
            posts.append(post)
    network = with_items(network, "posts", ((p.id, p) for p in posts))
    return with_items(network, "post_states", ((p.id, PostState()) for p in posts))


def deliver_connections(network: Network, ids: list[str], at: float, preloaded: bool) -> Network:
    arrivals = []
    for n, connection_id in _fresh(network.connections, ids):
        record = records.table(network.catalog, "connections").get(connection_id) or {}
        made = records.catalog_connection(
            network.catalog,
            connection_id,
            received_at=at - age(record) if preloaded else at,
            order=records.record_order(network.catalog, "connections", connection_id, n),
        )
        if made is not None:
            arrivals.append(made)
    network = with_items(network, "connections", ((c.id, c) for c, _ in arrivals))
    return with_items(network, "connection_states", ((c.id, s) for c, s in arrivals))


def add_conversation(network: Network, conversation_id: str) -> Network:
    if conversation_id in network.conversations:
        return network
    conversation = records.catalog_conversation(
        network.catalog, conversation_id, len(network.conversations)
    )
    if conversation is None:
        return network
    return with_items(network, "conversations", [(conversation_id, conversation)])


def deliver_conversations(network: Network, ids: list[str], at: float) -> Network:
    """Preloaded conversations with every catalog message of theirs (the original's rule),
    except those our catalog marks `arrivesLater` (sent by a `new_message` event)."""
    catalog = network.catalog
    for conversation_id in dict.fromkeys(ids):
        network = add_conversation(network, conversation_id)
        if conversation_id not in network.conversations:
            continue
        arrivals = [
            m
            for m in records.message_records(catalog, conversation_id)
            if not m.get("arrivesLater") and str(m["id"]) not in network.messages
        ]
        messages = [
            records.catalog_message(catalog, conversation_id, m, sent_at=at - age(m), order=n)
            for n, m in enumerate(arrivals)
        ]
        network = with_items(network, "messages", ((m.id, m) for m in messages))
        network = with_items(
            network,
            "message_states",
            (
                (str(m["id"]), MessageState(records.preloaded_read(catalog, conversation_id, m)))
                for m in arrivals
            ),
        )
    return network


def deliver_message(network: Network, message_id: str, at: float) -> Network:
    """One message arriving unread; its conversation is added first when it is not loaded."""
    catalog = network.catalog
    conversation_id = catalog.index(records.conversation_of_message).get(message_id)
    if conversation_id is None or message_id in network.messages:
        return network
    network = add_conversation(network, conversation_id)
    record = next(
        m for m in records.message_records(catalog, conversation_id) if m["id"] == message_id
    )
    message = records.catalog_message(catalog, conversation_id, record, sent_at=at, order=0)
    network = with_items(network, "messages", [(message_id, message)])
    return with_items(network, "message_states", [(message_id, MessageState(is_read=False))])


def deliver_notifications(network: Network, ids: list[str], at: float, preloaded: bool) -> Network:
    arrivals = []
    for n, notification_id in _fresh(network.notifications, ids):
        record = records.table(network.catalog, "notifications").get(notification_id) or {}
        made = records.catalog_notification(
            network.catalog,
            notification_id,
            at=at - age(record) if preloaded else at,
            order=records.record_order(network.catalog, "notifications", notification_id, n),
            keep_read=preloaded,
        )
        if made is not None:
            arrivals.append(made)
    network = with_items(network, "notifications", ((x.id, x) for x, _ in arrivals))
    return with_items(network, "notification_states", ((x.id, s) for x, s in arrivals))


def deliver_jobs(network: Network, ids: list[str], at: float, preloaded: bool) -> Network:
    jobs = []
    for n, job_id in _fresh(network.jobs, ids):
        record = records.table(network.catalog, "jobs").get(job_id) or {}
        job = records.catalog_job(
            network.catalog,
            job_id,
            posted_at=at - age(record) if preloaded else at,
            order=records.record_order(network.catalog, "jobs", job_id, n),
        )
        if job is not None:
            jobs.append(job)
    network = with_items(network, "jobs", ((j.id, j) for j in jobs))
    return with_items(network, "job_states", ((j.id, JobState()) for j in jobs))


# --- scenario events ------------------------------------------------------------------------------


class PreloadPosts(Payload):
    post_ids: list[str] = Field(default_factory=list, description='["*"] = every post')
    connection_ids: list[str] = Field(default_factory=list, description='["*"] = every request')
    conversation_ids: list[str] = Field(default_factory=list, description='["*"] = every thread')
    notification_ids: list[str] = Field(default_factory=list, description='["*"] = all')
    job_ids: list[str] = Field(default_factory=list, description='["*"] = every job')
    profile_view_count: int | None = Field(None, description="the self user's profile viewers")
    page_visitor_count: int | None = Field(
        None, description="visitors of the self user's company page"
    )
    connections_count: int | None = Field(None, description="the self user's connections")
    initial_connection_ids: list[str] | None = Field(None, description="user ids already connected")


def starting_stats(network: Network, payload: Mapping) -> ProfileStats:
    """The profile's numbers: the preload's, else the self user's catalog profile."""
    profile = records.profile_record(network.catalog, network.me.id)
    connected = tuple(payload.get("initial_connection_ids") or profile.get("connectedIds") or ())

    def number(key: str, profile_key: str, fallback: int = 0) -> int:
        value = payload.get(key)
        return int(value if value is not None else profile.get(profile_key) or fallback)

    return ProfileStats(
        profile_views=number("profile_view_count", "profileViews"),
        page_visitors=number("page_visitor_count", "pageVisitors"),
        connections=number("connections_count", "connections", len(connected)),
        connected_ids=connected,
    )


def reduce_preload_posts(network: Network, event: LoggedEvent) -> Network:
    """The starting network; preloaded items keep the catalog's read flags and statuses."""
    p, at, catalog = event.payload, event.at, network.catalog

    def ids(field: str, table: str) -> list[str]:
        return catalog.expand(ENVIRONMENT, table, p.get(field) or [])

    network = deliver_posts(network, ids("post_ids", "posts"), at, preloaded=True)
    network = deliver_connections(network, ids("connection_ids", "connections"), at, True)
    network = deliver_conversations(network, ids("conversation_ids", "messages"), at)
    network = deliver_notifications(network, ids("notification_ids", "notifications"), at, True)
    network = deliver_jobs(network, ids("job_ids", "jobs"), at, preloaded=True)
    return replace(network, stats=starting_stats(network, p))


class NewPost(Payload):
    post_id: str = Field(description="catalog post id")


class NewConnection(Payload):
    connection_id: str = Field(description="catalog connection request id")


class NewMessage(Payload):
    message_id: str = Field(description="id of a message inside a catalog conversation")


class NewNotification(Payload):
    notification_id: str = Field(description="catalog notification id")


class NewJob(Payload):
    job_id: str = Field(description="catalog job id")


def reduce_new_post(network: Network, event: LoggedEvent) -> Network:
    """A post appears at the top of the feed (the newest original raised its order likewise)."""
    return deliver_posts(network, [event.payload["post_id"]], event.at, preloaded=False)


def reduce_new_connection(network: Network, event: LoggedEvent) -> Network:
    return deliver_connections(network, [event.payload["connection_id"]], event.at, False)


def reduce_new_message(network: Network, event: LoggedEvent) -> Network:
    return deliver_message(network, event.payload["message_id"], event.at)


def reduce_new_notification(network: Network, event: LoggedEvent) -> Network:
    return deliver_notifications(network, [event.payload["notification_id"]], event.at, False)


def reduce_new_job(network: Network, event: LoggedEvent) -> Network:
    return deliver_jobs(network, [event.payload["job_id"]], event.at, preloaded=False)


EVENT_TYPES: Mapping[str, EventType] = MappingProxyType(
    {
        "preload_posts": EventType(
            schema=PreloadPosts,
            reduce=reduce_preload_posts,
            help="The network at the start: posts, invitations, threads, notifications, jobs.",
            catalog_refs={
                "post_ids": "posts",
                "connection_ids": "connections",
                "conversation_ids": "messages",
                "notification_ids": "notifications",
                "job_ids": "jobs",
            },
            preload=True,
        ),
        "new_post": EventType(
            NewPost,
            reduce_new_post,
            help="A post appears in the feed.",
            catalog_refs={"post_id": "posts"},
        ),
        "new_connection": EventType(
            NewConnection,
            reduce_new_connection,
            help="A connection request arrives.",
            catalog_refs={"connection_id": "connections"},
        ),
        "new_message": EventType(
            NewMessage, reduce_new_message, help="A message arrives, unread (its thread too)."
        ),
        "new_notification": EventType(
            NewNotification,
            reduce_new_notification,
            help="A notification arrives, unread.",
            catalog_refs={"notification_id": "notifications"},
        ),
        "new_job": EventType(
            NewJob, reduce_new_job, help="A job is posted.", catalog_refs={"job_id": "jobs"}
        ),
    }
)


# --- evaluation tables (the original's names and columns, so eval_sql runs unchanged) -----------

POSTS = Table(
    "posts",
    ("id TEXT PRIMARY KEY", "authorId TEXT", "content TEXT", "likes INTEGER", "shares INTEGER"),
)
POST_STATES = Table("post_states", ("post_id TEXT PRIMARY KEY", "isLiked INTEGER"))
CONNECTIONS = Table(
    "connections", ("id TEXT PRIMARY KEY", "userId TEXT", "name TEXT", "mutualConnections INTEGER")
)
CONNECTION_STATES = Table("connection_states", ("connection_id TEXT PRIMARY KEY", "status TEXT"))
MESSAGES = Table(
    "messages", ("id TEXT PRIMARY KEY", "conversationId TEXT", "senderId TEXT", "content TEXT")
)
MESSAGE_STATES = Table("message_states", ("message_id TEXT PRIMARY KEY", "isRead INTEGER"))
NOTIFICATIONS = Table(
    "notifications", ("id TEXT PRIMARY KEY", "type TEXT", "actorId TEXT", "content TEXT")
)
NOTIFICATION_STATES = Table(
    "notification_states", ("notification_id TEXT PRIMARY KEY", "isRead INTEGER")
)
JOBS = Table("jobs", ("id TEXT PRIMARY KEY", "title TEXT", "companyId TEXT", "location TEXT"))
JOB_STATES = Table("job_states", ("job_id TEXT PRIMARY KEY", "isApplied INTEGER"))


def materialize(network: Network, now: float, conn: sqlite3.Connection) -> None:
    """Write the ten tables. Nothing here moves between events: `now` is unused. Comments, images,
    times, job requirements and profile sections are not exposed (as in the original)."""
    n = network
    POSTS.write(
        conn,
        (
            (p.id, p.author.id, p.content, network_state.likes_now(n, p.id), p.shares)
            for p in n.posts.values()
        ),
    )
    POST_STATES.write(conn, ((i, s.is_liked) for i, s in n.post_states.items()))
    CONNECTIONS.write(
        conn, ((c.id, c.person.id, c.person.name, c.mutual) for c in n.connections.values())
    )
    CONNECTION_STATES.write(conn, ((i, s.status) for i, s in n.connection_states.items()))
    MESSAGES.write(
        conn, ((m.id, m.conversation_id, m.sender.id, m.content) for m in n.messages.values())
    )
    MESSAGE_STATES.write(conn, ((i, s.is_read) for i, s in n.message_states.items()))
    NOTIFICATIONS.write(
        conn, ((x.id, x.type, x.actor.id, x.content) for x in n.notifications.values())
    )
    NOTIFICATION_STATES.write(conn, ((i, s.is_read) for i, s in n.notification_states.items()))
    JOBS.write(conn, ((j.id, j.title, j.company.id, j.location) for j in n.jobs.values()))
    JOB_STATES.write(conn, ((i, s.is_applied) for i, s in n.job_states.items()))


def empty_network(catalog) -> Network:
    return Network(catalog=catalog, me=records.self_person(catalog))


def _opens_unread(network: Network, conversation_id: str) -> bool:
    return (
        conversation_id in network.conversations
        and network_state.unread_in(network, conversation_id) > 0
    )


MICRODIN = Environment(
    name=ENVIRONMENT,
    title="MicroDin",
    initial_state=empty_network,
    event_types=EVENT_TYPES,
    actions=ACTIONS,
    baselines=BASELINES,
    materialize=materialize,
    urlconf="apps.microdin.urls",
    implicit_actions=(
        # Opening a thread marks its messages read, as clicking it in the original does.
        ImplicitAction(
            page="messaging",
            param="conversation",
            action="open_conversation",
            payload=lambda conversation_id: {"conversation_id": conversation_id},
            applies=_opens_unread,
        ),
    ),
    sample_pages=sample_pages,
)
