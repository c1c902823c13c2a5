"""What the social feeds (MicroDin, MicroGram) share: members read with their profile on the app,
the pictures and comments of posts as the catalog gives them, and the decision on a new comment.

Only the logic that is the same in both lives here; each app keeps its own post, its own person
and where it stores the self user's comments. The post buttons' view step is `feed_views.act_on_post`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, Generic, TypeVar

from pydantic import Field

from apps.kit.deciding import checking, found, new_id, required_text
from apps.kit.fields import ItemId, Text
from apps.media.pictures import SUBJECTS
from events.registry import Action, PageStep, Reducer
from events.schemas import Payload

Member = TypeVar("Member")  # a person as the app shows them (its own `Person`)
FALLBACK_SUBJECT = "abstract"  # for a subject no scene is drawn for


class PostId(Payload):
    post_id: ItemId = Field(description="id of a post in the feed")


class CommentOnPost(PostId):
    text: Text = Field(description="the comment")


@dataclass(frozen=True)
class Picture:
    """A generated illustration (apps.media) of `subject`; the seed makes it one picture."""

    seed: str
    subject: str
    label: str = ""


@dataclass(frozen=True)
class Comment(Generic[Member]):
    """A comment under a post, by a person of the app it is in."""

    id: str
    author: Member
    text: str
    likes: int = 0
    at: float | None = None  # the self user's comments carry their time; the catalog's do not


# --- catalog records ---------------------------------------------------------------------------


def profile_record(catalog: Any, environment: str, user_id: str) -> Mapping[str, Any]:
    """A person's profile on the app: our catalog's `<environment>/profiles` record, else the
    original's, kept inside the user record under the app's name (`users.json`)."""
    record = catalog.table(environment, "profiles").get(user_id)
    if record is not None:
        return record
    return (catalog.users.get(user_id) or {}).get(environment) or {}


def members(
    catalog: Any,
    environment: str,
    member: Callable[[str, Mapping[str, Any], Mapping[str, Any]], Member],
) -> dict[str, Member]:
    """Every user of the catalog, in catalog order, as the app shows them:
    `member(user_id, user record, their profile on the app)`."""
    return {
        user_id: member(user_id, user, profile_record(catalog, environment, user_id))
        for user_id, user in catalog.users.items()
    }


def drawn_picture(record: Mapping[str, Any], default_subject: str) -> Picture | None:
    """Our records' `image {seed, subject, label}` (the seed defaults to the record's id), or None
    when the record has none."""
    image = record.get("image")
    if not isinstance(image, Mapping):
        return None
    subject = str(image.get("subject") or default_subject)
    return Picture(
        seed=str(image.get("seed") or record["id"]),
        subject=subject if subject in SUBJECTS else FALLBACK_SUBJECT,
        label=str(image.get("label") or ""),
    )


def file_picture(url: Any, subject_of: Callable[[str], str]) -> Picture:
    """The original's image URL: its file name is the seed and, dashes read as spaces, the label;
    `subject_of(seed)` is what the app draws for it."""
    stem = str(url).rsplit("/", 1)[-1].rsplit(".", 1)[0]
    return Picture(seed=stem, subject=subject_of(stem), label=stem.replace("-", " "))


def catalog_comments(
    record: Mapping[str, Any], post_id: str, person: Callable[[str | None], Member]
) -> tuple[Comment[Member], ...]:
    """The comments inside a catalog post, in order; one without an id is named after its place
    (`<post>-c<n>`), so the id stays the same from run to run."""
    return tuple(
        Comment(
            id=str(c.get("id", f"{post_id}-c{n}")),
            author=person(c.get("authorId")),
            text=str(c.get("text", "")),
            likes=int(c.get("likes") or 0),
        )
        for n, c in enumerate(record.get("comments") or (), 1)
        if isinstance(c, Mapping)
    )


# --- liking and commenting ------------------------------------------------------------------------


def comment_decider(where: str) -> Callable[[Any, dict], dict]:
    """decide() for `comment_post` on a state with `posts`: the post is there (else a 404 "no post
    '<id>' <where>"), the text is not blank; the comment's id is chosen here."""

    def decide(state: Any, payload: dict) -> dict:
        found(state.posts, payload["post_id"], "post", where)
        return {**payload, "text": required_text(payload, "text"), "id": new_id("user-comment")}

    return decide


def post_actions(
    where: str,
    liking: Callable[[bool], Reducer],
    reduce_comment: Reducer,
    page: Callable[[Any, dict], PageStep],
) -> dict[str, Action]:
    """`like_post`, `unlike_post` and `comment_post`: the same names, payloads and rules on every
    feed. The app says how a like is kept (`liking(is_liked)` → its reducer), where a comment is
    stored, and on which page a person does it."""
    post_exists = checking("posts", "post_id", "post", where)
    return {
        "like_post": Action(
            PostId,
            post_exists,
            liking(True),
            help="Like a post (its like count goes up by one).",
            page=page,
        ),
        "unlike_post": Action(
            PostId, post_exists, liking(False), help="Take a like back.", page=page
        ),
        "comment_post": Action(
            CommentOnPost,
            comment_decider(where),
            reduce_comment,
            help="Comment on a post as the self user.",
            page=page,
        ),
    }
