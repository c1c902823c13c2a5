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
from typing import Any

from apps.kit import social
from apps.microgram.state import (
    ENVIRONMENT,
    Activity,
    Conversation,
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


def table(catalog: Any, name: str) -> Mapping[str, Mapping[str, Any]]:
    return catalog.table(ENVIRONMENT, name)


def member(user_id: str, user: Mapping[str, Any], profile: Mapping[str, Any]) -> Person:
    """A catalog user as MicroGram shows them; `profile` holds their numbers on MicroGram."""
    return Person(
        id=user_id,
        name=str(user.get("name") or user_id),
        username=str(user.get("username") or user_id),
        bio=str(profile.get("bio") or user.get("bio") or ""),
        website=str(profile.get("website") or ""),
        followers=int(profile.get("followers") or 0),
        following=int(profile.get("following") or 0),
        posts_count=int(profile.get("postsCount") or 0),
        verified=bool(profile.get("isVerified")),
    )


def people(catalog: Any) -> Mapping[str, Person]:
    """Every person of the catalog as MicroGram shows them (built once per catalog)."""
    return social.members(catalog, ENVIRONMENT, member)


def person(catalog: Any, user_id: str | None) -> Person:
    found = catalog.index(people).get(user_id or "")
    return found if found is not None else Person(str(user_id or ""), UNKNOWN, UNKNOWN)


def self_person(catalog: Any) -> Person:
    me = catalog.self_user
    return person(catalog, me["id"]) if me else Person("me", "Me", "me")


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


def max_order(catalog: Any, name: str) -> int:
    return max((int(r.get("order") or 0) for r in table(catalog, name).values()), default=0)


def preload_age(catalog: Any, name: str, record: Mapping[str, Any]) -> float:
    """Seconds before the preload the item appeared: `ageMinutes`, else the original's
    fabricated age (10 minutes per order step below the table's highest order)."""
    minutes = record.get("ageMinutes")
    if minutes is None:
        steps = catalog.index(_max_orders).get(name, 0) - int(record.get("order") or 0)
        minutes = (steps + 1) * MINUTES_PER_ORDER_STEP
    return float(minutes) * 60


def _max_orders(catalog: Any) -> Mapping[str, int]:
    return {name: max_order(catalog, name) for name in ("posts", "stories", "messages", "activity")}


def catalog_post(catalog: Any, post_id: str, *, posted_at: float) -> Post | None:
    record = table(catalog, "posts").get(post_id)
    if record is None:
        return None
    return Post(
        id=post_id,
        author=person(catalog, record.get("authorId")),
        image=picture(record, "imageUrl"),
        caption=str(record.get("caption") or ""),
        location=str(record.get("location") or ""),
        likes=int(record.get("likes") or 0),
        comments=social.catalog_comments(record, post_id, lambda user_id: person(catalog, user_id)),
        is_target=bool(record.get("isTargetPost")),
        posted_at=posted_at,
        order=int(record.get("order") or 0),
    )


def catalog_story(catalog: Any, story_id: str, *, posted_at: float) -> Story | None:
    record = table(catalog, "stories").get(story_id)
    if record is None:
        return None
    return Story(
        id=story_id,
        author=person(catalog, record.get("authorId")),
        image=picture(record, "mediaUrl"),
        media_type=str(record.get("mediaType") or "image"),
        posted_at=posted_at,
        order=int(record.get("order") or 0),
    )


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


def catalog_conversation(
    catalog: Any, conversation_id: str, *, arrived_at: float
) -> Conversation | None:
    record = table(catalog, "messages").get(conversation_id)
    if record is None:
        return None
    me = self_person(catalog).id
    others = [p for p in record.get("participantIds") or () if p != me]
    messages = tuple(
        Message(
            id=str(m["id"]),
            sender=person(catalog, m.get("senderId")),
            text=str(m.get("text") or ""),
            order=int(m.get("order") or n),
        )
        for n, m in enumerate(record.get("messages") or ())
        if isinstance(m, Mapping) and "id" in m
    )
    return Conversation(
        id=conversation_id,
        other=person(catalog, others[0] if others else None),
        messages=tuple(sorted(messages, key=lambda m: m.order)),
        last_message=str(record.get("lastMessage") or (messages[-1].text if messages else "")),
        data=conversation_data(catalog, record),
        arrived_at=arrived_at,
        order=int(record.get("order") or 0),
    )


def initial_reads(catalog: Any, conversation_id: str) -> dict[str, bool]:
    """The read flag of each message as the catalog gives it (read when it says nothing)."""
    record = table(catalog, "messages").get(conversation_id) or {}
    return {
        str(m["id"]): bool(m.get("isRead", True))
        for m in record.get("messages") or ()
        if isinstance(m, Mapping) and "id" in m
    }


# The original's wording for each kind of activity without its own text.
ACTIVITY_PHRASES: Mapping[str, str] = {
    "like": "liked your photo.",
    "follow": "started following you.",
    "comment": "commented:",
    "mention": "mentioned you in a comment.",
}


def catalog_activity(catalog: Any, activity_id: str, *, posted_at: float) -> Activity | None:
    record = table(catalog, "activity").get(activity_id)
    if record is None:
        return None
    return Activity(
        id=activity_id,
        type=str(record.get("type") or "mention"),
        actor=person(catalog, record.get("actorId")),
        text=str(record.get("text") or ""),
        target_post_id=record.get("targetPostId"),
        posted_at=posted_at,
        order=int(record.get("order") or 0),
    )


def activity_read(catalog: Any, activity_id: str) -> bool:
    """Whether a preloaded activity item was already seen (the catalog's `isRead`)."""
    return bool((table(catalog, "activity").get(activity_id) or {}).get("isRead"))
