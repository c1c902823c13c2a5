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
from typing import Any

from apps.kit import social
from apps.microdin.state import (
    ENVIRONMENT,
    Company,
    Connection,
    ConnectionState,
    Conversation,
    Job,
    Message,
    Notification,
    NotificationState,
    Person,
    Post,
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


def table(catalog: Any, name: str) -> Mapping[str, Mapping[str, Any]]:
    return catalog.table(ENVIRONMENT, name)


def profile_record(catalog: Any, user_id: str) -> Mapping[str, Any]:
    """The person's MicroDin profile (company, headline, numbers on the network)."""
    return social.profile_record(catalog, ENVIRONMENT, user_id)


def company(catalog: Any, company_id: str | None, name: str = "") -> Company | None:
    if not company_id and not name:
        return None
    entity = catalog.entities.get(company_id) or table(catalog, "companies").get(company_id) or {}
    made_up = (company_id or "").removeprefix("company-").replace("-", " ").title()
    return Company(
        id=company_id or name,
        name=str(entity.get("name") or name or made_up),
        description=str(entity.get("description") or ""),
        industry=str(entity.get("industry") or ""),
    )


def people(catalog: Any) -> Mapping[str, Person]:
    """Every person of the catalog as a card shows them (built once per catalog)."""

    def member(user_id: str, user: Mapping[str, Any], profile: Mapping[str, Any]) -> Person:
        return Person(
            id=user_id,
            name=str(user.get("name") or UNKNOWN_MEMBER),
            title=str(profile.get("headline") or user.get("jobTitle") or ""),
            company=company(catalog, profile.get("companyId"), str(profile.get("company") or "")),
            location=str(user.get("location") or ""),
        )

    return social.members(catalog, ENVIRONMENT, member)


def catalog_people(catalog: Any) -> Mapping[str, Person]:
    """Every member by id, in catalog order (computed once per catalog)."""
    return catalog.index(people)


def person(catalog: Any, user_id: str | None) -> Person:
    found = catalog.index(people).get(user_id or "")
    return found if found is not None else Person(id=str(user_id or ""), name=UNKNOWN_MEMBER)


def self_person(catalog: Any) -> Person:
    me = catalog.self_user
    return person(catalog, me["id"]) if me else Person("me", "Me")


def age(record: Mapping[str, Any]) -> float:
    minutes = record.get("ageMinutes")
    return float(minutes) * 60 if minutes is not None else PRELOAD_AGE_S


def _order(record: Mapping[str, Any], fallback: int) -> int:
    value = record.get("order")
    return int(value) if isinstance(value, int | float) else fallback


def picture(record: Mapping[str, Any]) -> social.Picture | None:
    """Ours: `image {subject, label}`; the original: an `imageUrl` (its file name is the seed)."""
    drawn = social.drawn_picture(record, default_subject="office")
    url = record.get("imageUrl")
    if drawn is None and url:
        return social.file_picture(url, lambda seed: "office")
    return drawn


def catalog_post(catalog: Any, post_id: str, *, posted_at: float, order: int) -> Post | None:
    record = table(catalog, "posts").get(post_id)
    if record is None:
        return None
    return Post(
        id=post_id,
        author=person(catalog, record.get("authorId")),
        content=str(record.get("content", "")),
        likes=int(record.get("likes") or 0),
        shares=int(record.get("shares") or 0),
        comments=social.catalog_comments(record, post_id, lambda user_id: person(catalog, user_id)),
        posted_at=posted_at,
        order=order,
        image=picture(record),
    )


def catalog_connection(
    catalog: Any, connection_id: str, *, received_at: float, order: int
) -> tuple[Connection, ConnectionState] | None:
    record = table(catalog, "connections").get(connection_id)
    if record is None:
        return None
    connection = Connection(
        id=connection_id,
        person=person(catalog, record.get("userId")),
        mutual=int(record.get("mutualConnections") or 0),
        received_at=received_at,
        order=order,
    )
    status = str(record.get("status") or "pending")
    return connection, ConnectionState(status=status)


def conversation_of_message(catalog: Any) -> Mapping[str, str]:
    """message id → the id of the conversation record holding it (built once per catalog)."""
    return {
        str(m["id"]): conversation_id
        for conversation_id, record in table(catalog, "messages").items()
        for m in record.get("messages") or ()
        if isinstance(m, Mapping) and "id" in m
    }


def catalog_conversation(catalog: Any, conversation_id: str, order: int) -> Conversation | None:
    record = table(catalog, "messages").get(conversation_id)
    if record is None:
        return None
    me = self_person(catalog)
    others = [p for p in record.get("participantIds") or () if p != me.id]
    return Conversation(
        id=conversation_id,
        other=person(catalog, others[0] if others else None),
        order=_order(record, order),
    )


def message_records(catalog: Any, conversation_id: str) -> list[Mapping[str, Any]]:
    record = table(catalog, "messages").get(conversation_id) or {}
    return [m for m in record.get("messages") or () if isinstance(m, Mapping) and "id" in m]


def preloaded_read(catalog: Any, conversation_id: str, message: Mapping[str, Any]) -> bool:
    """A preloaded message's read flag: the record's `isRead`, else read unless it is among the
    conversation's last `unreadCount` messages from the other person (the original's records
    carry only that count)."""
    if "isRead" in message:
        return bool(message["isRead"])
    record = table(catalog, "messages").get(conversation_id) or {}
    me = self_person(catalog).id
    incoming = [
        m["id"]
        for m in message_records(catalog, conversation_id)
        if m.get("senderId") != me and not m.get("arrivesLater")
    ]
    unread = int(record.get("unreadCount") or 0)
    return message["id"] not in (incoming[-unread:] if unread else [])


def catalog_message(
    catalog: Any, conversation_id: str, record: Mapping[str, Any], *, sent_at: float, order: int
) -> Message:
    return Message(
        id=str(record["id"]),
        conversation_id=conversation_id,
        sender=person(catalog, record.get("senderId")),
        content=str(record.get("text", record.get("content", ""))),
        sent_at=sent_at,
        order=_order(record, order),
    )


def catalog_notification(
    catalog: Any, notification_id: str, *, at: float, order: int, keep_read: bool
) -> tuple[Notification, NotificationState] | None:
    record = table(catalog, "notifications").get(notification_id)
    if record is None:
        return None
    kind = str(record.get("type") or "other")
    notification = Notification(
        id=notification_id,
        type=kind,
        actor=person(catalog, record.get("actorId")),
        content=str(record.get("text") or DEFAULT_PHRASES.get(kind, "has a new update for you")),
        at=at,
        order=order,
        target_post_id=record.get("targetPostId"),
    )
    read = bool(record.get("isRead", False)) if keep_read else False
    return notification, NotificationState(is_read=read)


def catalog_job(catalog: Any, job_id: str, *, posted_at: float, order: int) -> Job | None:
    record = table(catalog, "jobs").get(job_id)
    if record is None:
        return None
    return Job(
        id=job_id,
        title=str(record.get("title", "")),
        company=company(catalog, record.get("companyId"), str(record.get("company") or ""))
        or Company(id="", name=UNKNOWN_MEMBER),
        location=str(record.get("location", "")),
        type=str(record.get("type") or "full-time"),
        description=str(record.get("description", "")),
        requirements=tuple(str(r) for r in record.get("requirements") or ()),
        applicants=int(record.get("applicants") or 0),
        posted_at=posted_at,
        order=order,
    )


def record_order(catalog: Any, name: str, item_id: str, fallback: int) -> int:
    return _order(table(catalog, name).get(item_id) or {}, fallback)
