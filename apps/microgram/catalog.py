"""Turning catalog records (SentinelBench format) into MicroGram values.

Tables of `microgram/`: `posts` (comments inside), `stories`, `messages` (one record per DM
thread, its messages inside), `activity` — the original's shapes — and, in our catalog,
`profiles` (each person's numbers on MicroGram). The original keeps that profile inside each user
record (`users.json` → `microgram`); both are read.

Images: our records carry `image {subject, label}` (a generated picture of that subject); the
original's carry an `imageUrl` / `mediaUrl`, whose file name becomes the seed. Our records may
carry `ageMinutes` (how long before the preload the item appeared); without it the age is made
from the catalog order, as the original did.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from functools import partial
from typing import Any

from apps.kit import social
from apps.kit.arrivals import Stamp
from apps.kit.feeds import Members, arrived_at, from_catalog, thread_messages
from apps.kit.records import Record, read, reader
from apps.microgram.state import (
    ENVIRONMENT,
    Activity,
    Conversation,
    Gram,
    Message,
    Person,
    Post,
    Story,
)

# Words in the original's image file names → the closest subject we can draw.
SUBJECT_HINTS: tuple[tuple[str, tuple[str, ...]], ...] = (
    ("food", ("food", "coffee", "pasta", "market", "dinner", "baking", "bread", "brunch", "tea")),
    ("pet", ("dog", "cat", "pet", "puppy")),
    ("city", ("city", "skyline", "street", "architecture", "opera", "temple", "bridge")),
    ("office", ("desk", "office", "workshop", "conference", "lab", "studio", "setup", "coding")),
    ("chart", ("analytics", "dashboard", "chart", "data")),
    ("people", ("team", "festival", "concert", "club", "party", "interview", "marathon")),
    ("abstract", ("art", "sketch", "calligraphy", "pottery", "design")),
)
MINUTES_PER_ORDER_STEP = 10  # the original's fabricated age: 10 minutes per order step
UNKNOWN = "microgram_user"


def member(
    catalog: Any, user_id: str, user: Mapping[str, Any], profile: Mapping[str, Any]
) -> Person:
    """A catalog user as MicroGram shows them; `profile` holds their numbers on MicroGram."""
    return read(
        Person,
        profile,
        id=user_id,
        name=str(user.get("name") or user_id),
        username=str(user.get("username") or user_id),
        bio=str(profile.get("bio") or user.get("bio") or ""),
    )


MEMBERS = Members(
    ENVIRONMENT,
    member,
    unknown=lambda user_id: Person(user_id, UNKNOWN, UNKNOWN),
    myself=Person("me", "Me", "me"),
)
person = MEMBERS.person  # (catalog, user id) → the member, or an unknown one


def guess_subject(seed: str) -> str:
    words = seed.lower()
    return next(
        (subject for subject, hints in SUBJECT_HINTS if any(h in words for h in hints)),
        "landscape",
    )


def picture(record: Mapping[str, Any], url_key: str) -> social.Picture:
    """Ours: `image {subject, label}`; the original: the URL under `url_key`, else the id."""
    drawn = social.drawn_picture(record, default_subject="abstract")
    return drawn or social.file_picture(record.get(url_key) or record["id"], guess_subject)


def _max_orders(catalog: Any) -> Mapping[str, int]:
    """Each table's highest `order` (built once per catalog)."""
    return {
        name: max(
            (int(r.get("order") or 0) for r in catalog.table(ENVIRONMENT, name).values()), default=0
        )
        for name in ("posts", "stories", "messages", "activity")
    }


def arrival(catalog: Any, name: str, record: Mapping[str, Any], stamp: Stamp) -> float:
    """When the item appeared: now; preloaded, `ageMinutes` before the preload, else the
    original's fabricated age (10 minutes per order step below the table's highest order)."""
    steps = catalog.index(_max_orders).get(name, 0) - int(record.get("order") or 0)
    return arrived_at(record, stamp, default_age_s=(steps + 1) * MINUTES_PER_ORDER_STEP * 60.0)


# --- items as they arrive (each the `make` of an apps.kit.arrivals.Delivery) ----------------------


@from_catalog(ENVIRONMENT, "posts")
def catalog_post(gram: Gram, post_id: str, record: Record, stamp: Stamp) -> Post:
    catalog = gram.catalog
    return read(
        Post,
        record,
        id=post_id,
        author=person(catalog, record.get("authorId")),
        image=picture(record, "imageUrl"),
        comments=social.catalog_comments(record, post_id, partial(person, catalog)),
        posted_at=arrival(catalog, "posts", record, stamp),
    )


catalog_story = reader(
    ENVIRONMENT,
    "stories",
    Story,
    author=lambda catalog, record, stamp: person(catalog, record.get("authorId")),
    image=lambda catalog, record, stamp: picture(record, "mediaUrl"),
    posted_at=lambda catalog, record, stamp: arrival(catalog, "stories", record, stamp),
)


@from_catalog(ENVIRONMENT, "activity")
def catalog_activity(
    gram: Gram, activity_id: str, record: Record, stamp: Stamp
) -> tuple[Activity, bool]:
    """An activity item and whether it is read: preloaded items keep the catalog's `isRead`
    (older ones were seen before the task); what arrives later is unread."""
    catalog = gram.catalog
    activity = read(
        Activity,
        record,
        id=activity_id,
        actor=person(catalog, record.get("actorId")),
        posted_at=arrival(catalog, "activity", record, stamp),
    )
    return activity, stamp.preloaded and bool(record.get("isRead"))


# --- DM threads: one record per thread, its messages inside ---------------------------------------


def conversation_data(catalog: Any, record: Mapping[str, Any]) -> str:
    """The thread as the original's `messages.data`: the record, its participants resolved and
    each message's sender named. Non-ASCII stays as written, so LIKE matches accented words
    (the original escaped them)."""
    data = dict(record)
    data["participants"] = [
        {"id": p.id, "username": p.username, "name": p.name}
        for p in (person(catalog, i) for i in record.get("participantIds") or ())
    ]
    data["messages"] = [
        {**m, "senderName": person(catalog, m.get("senderId")).name}
        for m in record.get("messages") or ()
        if isinstance(m, Mapping)
    ]
    return json.dumps(data, ensure_ascii=False)


@from_catalog(ENVIRONMENT, "messages")
def catalog_conversation(
    gram: Gram, conversation_id: str, record: Record, stamp: Stamp
) -> Conversation:
    catalog = gram.catalog
    messages = tuple(
        read(
            Message,
            m,
            id=str(m["id"]),
            sender=person(catalog, m.get("senderId")),
            order=int(m.get("order") or n),
        )
        for n, m in enumerate(record.get("messages") or ())
        if isinstance(m, Mapping) and "id" in m
    )
    return read(
        Conversation,
        record,
        id=conversation_id,
        other=MEMBERS.other_in(catalog, record),
        messages=tuple(sorted(messages, key=lambda m: m.order)),
        last_message=str(record.get("lastMessage") or (messages[-1].text if messages else "")),
        data=conversation_data(catalog, record),
        arrived_at=arrival(catalog, "messages", record, stamp),
    )


def initial_reads(catalog: Any, conversation_id: str) -> dict[str, bool]:
    """The read flag of each message as the catalog gives it (read when it says nothing)."""
    record = catalog.table(ENVIRONMENT, "messages").get(conversation_id)
    return {str(m["id"]): bool(m.get("isRead", True)) for m in thread_messages(record)}
