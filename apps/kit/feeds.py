"""What the social feeds (MicroDin, MicroGram) share beyond `social.py`: their members as a
catalog index, when a preloaded item appeared, the likes a post shows, the one-to-one threads,
and the rules and pages of the actions both apps have.

Each app keeps its own items (a post, a person, a thread) and its own wording; only logic that is
the same in both lives here. The views' helpers are in `feed_views`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import partial, wraps
from typing import Any, Generic, NamedTuple, TypeVar
from urllib.parse import quote

from pydantic import Field

from apps.kit import social
from apps.kit.arrivals import Stamp
from apps.kit.deciding import checking, found, new_id, required_text
from apps.kit.fields import ItemId
from apps.kit.state import setting, with_items
from apps.kit.tables import Table
from events.registry import Action, ImplicitAction, LoggedEvent, PageStep, Reducer
from events.schemas import Payload

Member = TypeVar("Member")  # a person as the app shows them (its own `Person`)
Make = Callable[[Any, str, Stamp], Any]  # a Delivery's make: (state, item id, stamp) → item


# --- members -------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Members(Generic[Member]):
    """Every user of the catalog as the app shows them, built once per catalog.

    `make(catalog, user_id, user record, their profile on the app)` builds one; `unknown(id)` is
    what an id the catalog does not know shows (a deleted account); `myself` the self user of a
    catalog that names none.
    """

    environment: str
    make: Callable[[Any, str, Mapping[str, Any], Mapping[str, Any]], Member]
    unknown: Callable[[str], Member]
    myself: Member

    def everyone(self, catalog: Any) -> Mapping[str, Member]:
        """id → member, in catalog order."""
        return catalog.index(self._build)

    def _build(self, catalog: Any) -> Mapping[str, Member]:
        return social.members(catalog, self.environment, partial(self.make, catalog))

    def person(self, catalog: Any, user_id: str | None) -> Member:
        member = self.everyone(catalog).get(user_id or "")
        return member if member is not None else self.unknown(str(user_id or ""))

    def me(self, catalog: Any) -> Member:
        me = catalog.self_user
        return self.person(catalog, me["id"]) if me else self.myself

    def profile(self, catalog: Any, user_id: str) -> Mapping[str, Any]:
        """The person's profile on the app (their numbers, headline, company…)."""
        return social.profile_record(catalog, self.environment, user_id)

    def other_in(self, catalog: Any, thread: Mapping[str, Any]) -> Member:
        """The person a one-to-one thread record is with: its participant who is not the self
        user (the original's records list both)."""
        me: Any = self.me(catalog)
        others = [p for p in thread.get("participantIds") or () if p != me.id]
        return self.person(catalog, others[0] if others else None)


# --- catalog records -----------------------------------------------------------------------------


def from_catalog(environment: str, table: str) -> Callable[[Callable[..., Any]], Make]:
    """Decorator for the `make` of a `Delivery`: `make(state, item_id, record, stamp)` is given
    the item's record of the catalog table `<environment>/<table>`; an id the table lacks makes
    nothing (scenario validation names it to the author before a run starts)."""

    def decorate(make: Callable[..., Any]) -> Make:
        @wraps(make)
        def made(state: Any, item_id: str, stamp: Stamp) -> Any:
            record = state.catalog.table(environment, table).get(item_id)
            return None if record is None else make(state, item_id, record, stamp)

        return made

    return decorate


def arrived_at(record: Mapping[str, Any], stamp: Stamp, default_age_s: float) -> float:
    """When an item appeared: now; or, preloaded, `ageMinutes` before the preload when our record
    says, else `default_age_s` before it (the original fabricated every preloaded item's age)."""
    if not stamp.preloaded:
        return stamp.at
    minutes = record.get("ageMinutes")
    return stamp.at - (float(minutes) * 60 if minutes is not None else default_age_s)


def thread_messages(thread: Mapping[str, Any] | None) -> list[Mapping[str, Any]]:
    """The messages inside a catalog thread record that have an id, in record order."""
    messages = (thread or {}).get("messages") or ()
    return [m for m in messages if isinstance(m, Mapping) and "id" in m]


# --- questions -----------------------------------------------------------------------------------


def likes_now(state: Any, post_id: str) -> int:
    """The post's like count with the self user's like counted once (the original adjusted the
    delivered count by ±1 as the heart was toggled)."""
    return state.posts[post_id].likes + int(state.post_states[post_id].is_liked)


def thread_with(state: Any, user_id: str) -> str | None:
    """The one-to-one thread with that person, if there is one."""
    return next((c.id for c in state.conversations.values() if c.other.id == user_id), None)


def counting(field: str, **values: Any) -> Callable[[Any], int]:
    """A count of the state (a baseline, a badge): how many records `state.<field>` holds, or,
    given `values`, how many of them have those attributes (`is_read=False`: the unread)."""

    def count(state: Any) -> int:
        records = getattr(state, field)
        if not values:
            return len(records)
        wanted = values.items()
        return sum(1 for r in records.values() if all(getattr(r, k) == v for k, v in wanted))

    return count


# --- evaluation tables ---------------------------------------------------------------------------


class PostRow(NamedTuple):
    """A row of the `posts` table: the post and the likes it shows now."""

    post: Any
    likes: int


def post_rows(state: Any, now: float) -> list[PostRow]:
    return [PostRow(post, likes_now(state, post.id)) for post in state.posts.values()]


# --- actions -------------------------------------------------------------------------------------


class ConversationId(Payload):
    conversation_id: ItemId = Field(description="id of a one-to-one thread (a conversation)")


def post_flag(**changes: bool) -> Reducer:
    """A reducer setting flags of the post's user-side record (liked, saved, viewed)."""
    return setting("post_states", "post_id", **changes)


def liking(is_liked: bool) -> Reducer:
    """How a feed keeps the self user's like (`social.post_actions` asks)."""
    return post_flag(is_liked=is_liked)


def item_action(
    schema: type[Payload], items: str, what: str, where: str
) -> Callable[[Reducer, str, Callable[[Any, dict], PageStep]], Action]:
    """The actions on one kind of item whose only rule is that the item is there (a save, a
    mark-read): the payload's one field (`story_id`…) names it among `state.<items>`, else a 404
    "no <what> '<id>' <where>". Returns `on(reduce, help, page)`, one such action."""
    (key,) = schema.model_fields
    exists = checking(items, key, what, where)

    def on(reduce: Reducer, help: str, page: Callable[[Any, dict], PageStep]) -> Action:
        return Action(schema, exists, reduce, help=help, page=page)

    return on


def sending(field: str, prefix: str, where: str) -> Callable[[Any, dict], dict]:
    """decide() for `send_message`: the thread is there, `payload[field]` is not blank; the
    message's id (`<prefix>-…`) is chosen here."""

    def decide(state: Any, payload: dict) -> dict:
        found(state.conversations, payload["conversation_id"], "conversation", where)
        return {**payload, field: required_text(payload, field), "id": new_id(prefix)}

    return decide


def starting(thread: Callable[[Any, LoggedEvent], Any]) -> Reducer:
    """The reducer of `start_conversation`: the thread `thread(state, event)` made, unless the
    decided `conversation_id` is one the state has already (the existing thread is reused)."""

    def reduce(state: Any, event: LoggedEvent) -> Any:
        if event.payload["conversation_id"] in state.conversations:
            return state
        conversation = thread(state, event)
        return with_items(state, "conversations", [(conversation.id, conversation)])

    return reduce


# --- where a person does it (Action.page) ---------------------------------------------------------


def post_page(path: str, where: str, *, form: bool = True) -> Callable[[Any, dict], PageStep]:
    """The post's own page, `<path><post id>/`: its buttons (and the comment's `text`), or, with
    `form` False, opening it is the action."""

    def page(state: Any, payload: dict) -> PageStep:
        found(state.posts, payload["post_id"], "post", where)
        fields = {"text": payload["text"]} if "text" in payload else {}
        return PageStep(f"{path}{quote(payload['post_id'])}/", fields if form else None)

    return page


def thread_page(
    path: Callable[[str], str], field: str, where: str
) -> Callable[[Any, dict], PageStep]:
    """The open thread at `path(conversation id)`: opening it is the action, or its form sends
    `payload[field]`."""

    def page(state: Any, payload: dict) -> PageStep:
        found(state.conversations, payload["conversation_id"], "conversation", where)
        form = {field: payload[field]} if field in payload else None
        return PageStep(path(payload["conversation_id"]), form)

    return page


def profile_page(path: str) -> Callable[[Any, dict], PageStep]:
    """The person's profile `<path><user id>/`, whose buttons (follow, message…) act on them."""
    return lambda state, payload: PageStep(f"{path}{quote(payload['user_id'])}/", {})


def opening(
    page: str,
    param: str,
    action: str,
    applies: Callable[[Any, str], bool],
    *,
    key: str | None = None,
) -> ImplicitAction:
    """Opening the page `page` with `param` (a thread, a post…) performs `action`
    `{key: value}` (`key` defaults to `param`) when `applies(state, value)`: reloading an opened
    item changes nothing."""
    field = key or param
    return ImplicitAction(page, param, action, lambda value: {field: value}, applies)


def posts_table(text: tuple[str, str], last: tuple[str, str]) -> Table:
    """`posts`: id, author, the post's text (`text`: its column and getter), its likes as shown
    now, and the one column the site adds last (`last`)."""
    return Table(
        "posts",
        post_rows,
        {
            "id TEXT PRIMARY KEY": "post.id",
            "authorId TEXT": "post.author.id",
            text[0]: text[1],
            "likes INTEGER": "likes",
            last[0]: last[1],
        },
    )
