"""Turning catalog records (SentinelBench format) into MicroDin values.

Tables of `microdin/`: `posts`, `connections`, `messages` (one record per conversation, its
messages inside), `notifications`, `jobs` — the original's shapes — and, in our catalog,
`profiles` (each person's company and numbers on the network). The original keeps that profile
inside each user record (`users.json` → `microdin`); both are read. Companies are the shared
entities (`entities.json`), else the profile's company name, else a name made from the id.

Our records may carry `ageMinutes`: how long before the preload the item appeared (the original
stamps every preloaded item five minutes before the start).
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import partial
from typing import Any

from apps.kit import social
from apps.kit.arrivals import Stamp
from apps.kit.feeds import Members, arrived_at, from_catalog, thread_messages
from apps.kit.records import Record, read, reader
from apps.microdin.state import (
    ENVIRONMENT,
    Company,
    Connection,
    ConnectionState,
    Conversation,
    Job,
    Message,
    Network,
    Notification,
    Person,
    Post,
    ReadState,
)

PRELOAD_AGE_S = 300.0
UNKNOWN_MEMBER = "MicroDin member"
# The original's wording for a notification without its own text.
DEFAULT_PHRASES: Mapping[str, str] = {
    "like": "liked your post",
    "comment": "commented on your post",
    "connection": "sent you a connection request",
    "mention": "mentioned you in a post",
    "job": "A new job matches your profile",
    "profile_view": "viewed your profile",
}


def company(catalog: Any, company_id: str | None, name: str = "") -> Company | None:
    if not company_id and not name:
        return None
    entity = (
        catalog.entities.get(company_id)
        or catalog.table(ENVIRONMENT, "companies").get(company_id)
        or {}
    )
    made_up = (company_id or "").removeprefix("company-").replace("-", " ").title()
    return read(
        Company, entity, id=company_id or name, name=str(entity.get("name") or name or made_up)
    )


def member(
    catalog: Any, user_id: str, user: Mapping[str, Any], profile: Mapping[str, Any]
) -> Person:
    """Someone as a card shows them; `profile` holds their company and headline on MicroDin."""
    return Person(
        id=user_id,
        name=str(user.get("name") or UNKNOWN_MEMBER),
        title=str(profile.get("headline") or user.get("jobTitle") or ""),
        company=company(catalog, profile.get("companyId"), str(profile.get("company") or "")),
        location=str(user.get("location") or ""),
    )


MEMBERS = Members(
    ENVIRONMENT,
    member,
    unknown=lambda user_id: Person(id=user_id, name=UNKNOWN_MEMBER),
    myself=Person("me", "Me"),
)
person = MEMBERS.person  # (catalog, user id) → the member, or an unknown one


def _order(record: Mapping[str, Any], fallback: int) -> int:
    value = record.get("order")
    return int(value) if isinstance(value, int | float) else fallback


def appeared(catalog: Any, record: Record, stamp: Stamp) -> float:
    """When the item appeared (`feeds.arrived_at`)."""
    return arrived_at(record, stamp, PRELOAD_AGE_S)


def place(catalog: Any, record: Record, stamp: Stamp) -> int:
    """Its place among equal times: the record's `order`, else its place in the delivery."""
    return _order(record, stamp.order)


def picture(record: Mapping[str, Any]) -> social.Picture | None:
    """Ours: `image {subject, label}`; the original: an `imageUrl` (its file name is the seed)."""
    drawn = social.drawn_picture(record, default_subject="office")
    url = record.get("imageUrl")
    return drawn or (social.file_picture(url, lambda seed: "office") if url else None)


def employer(catalog: Any, record: Record, stamp: Stamp) -> Company:
    """A job's company; one its record does not name reads as a member's."""
    found = company(catalog, record.get("companyId"), str(record.get("company") or ""))
    return found or Company(id="", name=UNKNOWN_MEMBER)


# --- items as they arrive (each the `make` of an apps.kit.arrivals.Delivery) ----------------------


@from_catalog(ENVIRONMENT, "posts")
def catalog_post(network: Network, post_id: str, record: Record, stamp: Stamp) -> Post:
    catalog = network.catalog
    return read(
        Post,
        record,
        id=post_id,
        author=person(catalog, record.get("authorId")),
        comments=social.catalog_comments(record, post_id, partial(person, catalog)),
        posted_at=appeared(catalog, record, stamp),
        order=place(catalog, record, stamp),
        image=picture(record),
    )


@from_catalog(ENVIRONMENT, "connections")
def catalog_connection(
    network: Network, connection_id: str, record: Record, stamp: Stamp
) -> tuple[Connection, ConnectionState]:
    """An invitation, with the status the catalog gives it (pending unless it says)."""
    catalog = network.catalog
    connection = read(
        Connection,
        record,
        id=connection_id,
        person=person(catalog, record.get("userId")),
        received_at=appeared(catalog, record, stamp),
        order=place(catalog, record, stamp),
    )
    return connection, read(ConnectionState, record)


@from_catalog(ENVIRONMENT, "notifications")
def catalog_notification(
    network: Network, notification_id: str, record: Record, stamp: Stamp
) -> tuple[Notification, ReadState]:
    """A notification: preloaded, with the catalog's read flag; arriving later, unread."""
    catalog = network.catalog
    kind = str(record.get("type") or "other")
    notification = read(
        Notification,
        record,
        id=notification_id,
        type=kind,
        actor=person(catalog, record.get("actorId")),
        content=str(record.get("text") or DEFAULT_PHRASES.get(kind, "has a new update for you")),
        at=appeared(catalog, record, stamp),
        order=place(catalog, record, stamp),
    )
    read_flag = bool(record.get("isRead", False)) and stamp.preloaded
    return notification, ReadState(is_read=read_flag)


catalog_job = reader(
    ENVIRONMENT,
    "jobs",
    Job,
    company=employer,
    posted_at=appeared,
    order=place,
    posted_during_run=lambda catalog, record, stamp: not stamp.preloaded,
)


# --- threads: one record per conversation, its messages inside -----------------------------------


@from_catalog(ENVIRONMENT, "messages")
def catalog_conversation(
    network: Network, conversation_id: str, record: Record, stamp: Stamp
) -> Conversation:
    """A thread, listed after those there are unless its record says where."""
    order = _order(record, len(network.conversations) + stamp.order)
    return Conversation(conversation_id, MEMBERS.other_in(network.catalog, record), order)


def message_index(catalog: Any) -> Mapping[str, tuple[str, Mapping[str, Any]]]:
    """message id → (the id of the conversation record holding it, the message's record)."""
    return {
        str(m["id"]): (conversation_id, m)
        for conversation_id, record in catalog.table(ENVIRONMENT, "messages").items()
        for m in thread_messages(record)
    }


def message_records(catalog: Any, conversation_id: str) -> list[Mapping[str, Any]]:
    return thread_messages(catalog.table(ENVIRONMENT, "messages").get(conversation_id))


def catalog_message(
    network: Network, message_id: str, stamp: Stamp
) -> tuple[Message, ReadState] | None:
    """A message in its thread: preloaded, with the catalog's read flag; arriving later, unread."""
    found = network.catalog.index(message_index).get(message_id)
    if found is None:
        return None
    catalog = network.catalog
    conversation_id, record = found
    message = read(
        Message,
        record,
        id=message_id,
        conversation_id=conversation_id,
        sender=person(catalog, record.get("senderId")),
        sent_at=appeared(catalog, record, stamp),
        order=place(catalog, record, stamp),
    )
    read_flag = stamp.preloaded and preloaded_read(catalog, conversation_id, record)
    return message, ReadState(is_read=read_flag)


def preloaded_read(catalog: Any, conversation_id: str, message: Mapping[str, Any]) -> bool:
    """A preloaded message's read flag: the record's `isRead`, else read unless it is among the
    conversation's last `unreadCount` messages from the other person (the original's records
    carry only that count)."""
    if "isRead" in message:
        return bool(message["isRead"])
    record = catalog.table(ENVIRONMENT, "messages").get(conversation_id) or {}
    me = MEMBERS.me(catalog).id
    incoming = [
        m["id"]
        for m in message_records(catalog, conversation_id)
        if m.get("senderId") != me and not m.get("arrivesLater")
    ]
    unread = int(record.get("unreadCount") or 0)
    return message["id"] not in (incoming[-unread:] if unread else [])
