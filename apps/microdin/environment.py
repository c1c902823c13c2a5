"""MicroDin's registration with the core: scenario events, baselines, evaluation tables.

Scenario events (SentinelBench format):
- `preload_posts {post_ids, connection_ids, conversation_ids, notification_ids, job_ids}` — the
  network as the task starts (each list may be `["*"]`; a conversation comes with all of its
  messages). Optional numbers for the profile: `profile_view_count`, `page_visitor_count`,
  `connections_count`, `initial_connection_ids`. Baselines are measured right after it.
- `new_post {post_id}`, `new_connection {connection_id}`, `new_message {message_id}`,
  `new_notification {notification_id}`, `new_job {job_id}` — one item arriving now (a message
  or notification unread, a job not applied to).
- `close_job {job_id}` — the employer stops taking applications: the posting stays in the
  list, marked as LinkedIn marks it, "No longer accepting applications", and loses its Apply
  button (apps.kit.retractions).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import replace

from pydantic import Field

from apps.kit.arrivals import Delivery, arrival, event_types, preload
from apps.kit.counts import ShownCount, untimed
from apps.kit.environments import declare
from apps.kit.feeds import opening, posts_table
from apps.kit.retractions import retraction, window
from apps.kit.tables import Table, item_states, tables
from apps.microdin import catalog as records
from apps.microdin import state as network_state
from apps.microdin.state import ENVIRONMENT, JobState, Network, PostState, ProfileStats
from events.registry import counted
from events.schemas import Payload

# Counted right after the preload, by the core (the original's names: baseline_<name>).
BASELINES = counted(
    {
        "post_count": network_state.post_count,
        "pending_connection_count": network_state.pending_connection_count,
        "unread_message_count": network_state.unread_message_count,
        "unread_conversation_count": network_state.unread_conversation_count,
        "unread_notification_count": network_state.unread_notification_count,
        "job_count": network_state.job_count,
        "applied_job_count": network_state.applied_job_count,
    }
)


def _not_a_strangers_profile(network: Network, path: str) -> bool:
    """Another member's profile shows their own connections."""
    return not path.startswith("in/") or path == f"in/{network.me.id}/"


def _opens_unread(network: Network, conversation_id: str) -> bool:
    return (
        conversation_id in network.conversations
        and network_state.unread_in(network, conversation_id) > 0
    )


# The numbers shown in more than one place (apps.kit.counts): the nav badges, the home page's
# card, My Network, the profile.
SHOWN_COUNTS = (
    ShownCount(
        "connections",
        untimed(network_state.connections_count),
        # ("Profile viewers 87 Connections 412": the card's figures sit side by side)
        ("Connections {n}", "(?<!viewers ){n} Connections?", "{n} connections?"),
        on=_not_a_strangers_profile,
    ),
    ShownCount(
        "pending invitations",
        untimed(network_state.pending_connection_count),
        ("{n} pending invitations?", r"Invitations \({n}\)", "Invitations {n}", "Show all {n}"),
    ),
    ShownCount(
        "unread messages", untimed(network_state.unread_message_count), ("{n} unread messages?",)
    ),
    ShownCount(
        "unread notifications",
        untimed(network_state.unread_notification_count),
        ("{n} unread notifications?",),
    ),
    ShownCount("jobs", untimed(network_state.job_count), ("{n} jobs? on MicroDin",)),
)


# --- delivering catalog items (apps.kit.arrivals: an id already present is left as it is) -------

deliver_posts = Delivery("posts", records.catalog_post, states="post_states", fresh=PostState)
deliver_connections = Delivery(
    "connections", records.catalog_connection, states="connection_states"
)
deliver_notifications = Delivery(
    "notifications", records.catalog_notification, states="notification_states"
)
deliver_jobs = Delivery("jobs", records.catalog_job, states="job_states", fresh=JobState)


deliver_threads = Delivery("conversations", records.catalog_conversation)
deliver_message_records = Delivery("messages", records.catalog_message, states="message_states")


def deliver_conversations(
    network: Network, ids: Iterable[str], at: float, *, preloaded: bool
) -> Network:
    """Conversations with every catalog message of theirs (the original's rule), except those
    our catalog marks `arrivesLater` (sent by a `new_message` event)."""
    for conversation_id in dict.fromkeys(ids):
        network = deliver_threads(network, [conversation_id], at, preloaded=preloaded)
        if conversation_id in network.conversations:
            messages = records.message_records(network.catalog, conversation_id)
            now = [str(m["id"]) for m in messages if not m.get("arrivesLater")]
            network = deliver_message_records(network, now, at, preloaded=preloaded)
    return network


def deliver_messages(network: Network, ids: Iterable[str], at: float, *, preloaded: bool):
    """Messages, each into its thread (which arrives first when it is not there yet)."""
    ids, index = list(ids), network.catalog.index(records.message_index)
    for message_id in ids:
        if message_id in index and message_id not in network.messages:
            thread_id = index[message_id][0]
            network = deliver_threads(network, [thread_id], at, preloaded=preloaded)
    return deliver_message_records(network, ids, at, preloaded=preloaded)


# --- scenario events ------------------------------------------------------------------------------


class ProfileNumbers(Payload):
    """The preload's numbers for the self user's profile (else their catalog profile's)."""

    profile_view_count: int | None = Field(None, description="the self user's profile viewers")
    page_visitor_count: int | None = Field(
        None, description="visitors of the self user's company page"
    )
    connections_count: int | None = Field(None, description="the self user's connections")
    initial_connection_ids: list[str] | None = Field(None, description="user ids already connected")


def starting_stats(network: Network, payload: Mapping, at: float) -> Network:
    """The profile's numbers: the preload's, else the self user's catalog profile."""
    profile = records.MEMBERS.profile(network.catalog, network.me.id)
    connected = tuple(payload.get("initial_connection_ids") or profile.get("connectedIds") or ())

    def number(key: str, profile_key: str, fallback: int = 0) -> int:
        value = payload.get(key)
        return int(value if value is not None else profile.get(profile_key) or fallback)

    stats = ProfileStats(
        profile_views=number("profile_view_count", "profileViews"),
        page_visitors=number("page_visitor_count", "pageVisitors"),
        connections=number("connections_count", "connections", len(connected)),
        connected_ids=connected,
    )
    return replace(network, stats=stats)


EVENT_TYPES = event_types(
    preload(
        "preload_posts",
        {
            "post_ids": ("posts", deliver_posts),
            "connection_ids": ("connections", deliver_connections),
            "conversation_ids": ("messages", deliver_conversations),
            "notification_ids": ("notifications", deliver_notifications),
            "job_ids": ("jobs", deliver_jobs),
        },
        base=ProfileNumbers,
        then=starting_stats,
        environment=ENVIRONMENT,
        help="The network at the start: posts, invitations, threads, notifications, jobs.",
    ),
    arrival("new_post", "post_id", "posts", deliver_posts, help="A post appears in the feed."),
    arrival(
        "new_connection",
        "connection_id",
        "connections",
        deliver_connections,
        help="A connection request arrives.",
        description="catalog connection request id",
    ),
    # A message is not a row of a table (it sits inside its conversation's record): no reference.
    arrival(
        "new_message",
        "message_id",
        None,
        deliver_messages,
        help="A message arrives, unread (its thread too).",
        description="id of a message inside a catalog conversation",
    ),
    arrival(
        "new_notification",
        "notification_id",
        "notifications",
        deliver_notifications,
        help="A notification arrives, unread.",
    ),
    arrival("new_job", "job_id", "jobs", deliver_jobs, help="A job is posted."),
    retraction(
        "close_job",
        "job_id",
        "jobs",
        "jobs",
        help='Its employer closes a posting: "No longer accepting applications" replaces Apply.',
    ),
)


# --- evaluation tables (the original's names and columns, so eval_sql runs unchanged) -----------
# Nothing here moves between events: `now` is unused. Comments, images, times, job requirements
# and profile sections are not exposed (as in the original).

materialize = tables(
    posts_table(("content TEXT", "post.content"), ("shares INTEGER", "post.shares")),
    item_states("post", {"isLiked INTEGER": "is_liked"}),
    Table.items(
        "connections",
        {
            "id TEXT PRIMARY KEY": "id",
            "userId TEXT": "person.id",
            "name TEXT": "person.name",
            "mutualConnections INTEGER": "mutual",
        },
    ),
    item_states("connection", {"status TEXT": "status"}),
    Table.items(
        "messages",
        {
            "id TEXT PRIMARY KEY": "id",
            "conversationId TEXT": "conversation_id",
            "senderId TEXT": "sender.id",
            "content TEXT": "content",
        },
    ),
    item_states("message", {"isRead INTEGER": "is_read"}),
    Table.items(
        "notifications",
        {
            "id TEXT PRIMARY KEY": "id",
            "type TEXT": "type",
            "actorId TEXT": "actor.id",
            "content TEXT": "content",
        },
    ),
    item_states("notification", {"isRead INTEGER": "is_read"}),
    Table.items(
        "jobs",
        {
            "id TEXT PRIMARY KEY": "id",
            "title TEXT": "title",
            "companyId TEXT": "company.id",
            "location TEXT": "location",
            **window("posted_at"),
        },
    ),
    item_states("job", {"isApplied INTEGER": "is_applied"}),
)


IMPLICIT_ACTIONS = (
    # Opening a thread marks its messages read, as clicking it in the original does.
    opening("messaging", "conversation", "open_conversation", _opens_unread, key="conversation_id"),
)


MICRODIN = declare(
    __name__,
    title="MicroDin",
    initial_state=lambda catalog: Network(catalog, me=records.MEMBERS.me(catalog)),
)
