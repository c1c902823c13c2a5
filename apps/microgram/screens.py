"""What each MicroGram screen shows: pure functions of the state, memoised per state.

Rows are small frozen values (a card, a bubble, a thread row) so a page can render each through
`render_fragment` once per distinct input.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass

from apps.kit.derived import per_state
from apps.kit.feeds import likes_now
from apps.kit.retractions import present
from apps.microgram.catalog import MEMBERS, person
from apps.microgram.state import (
    Activity,
    Conversation,
    Gram,
    Person,
    Post,
    Story,
    comments_of,
    is_following,
    known_people,
    newest_first,
    unread_activity_count,
    unread_conversation_count,
    unread_in,
)

SUGGESTIONS_SHOWN = 5
SEARCH_RESULTS = 30


@dataclass(frozen=True)
class PostCard:
    post: Post
    likes: int
    is_liked: bool
    is_saved: bool
    comment_count: int


@dataclass(frozen=True)
class StoryBubble:
    story: Story
    viewed: bool


@dataclass(frozen=True)
class ThreadRow:
    conversation: Conversation
    preview: str
    unread: int
    at: float


@dataclass(frozen=True)
class Bubble:
    """One message in an open thread."""

    mine: bool
    sender: Person
    text: str
    post: Post | None  # a shared post


@dataclass(frozen=True)
class ActivityRow:
    item: Activity
    unread: bool
    post: Post | None  # the post it is about, when it is in the feed
    follows_back: bool  # a follow: whether the self user follows them


@dataclass(frozen=True)
class Badges:
    activity: int  # unread activity items
    direct: int  # threads with unread messages


@dataclass(frozen=True)
class ProfileView:
    person: Person
    is_self: bool
    followed: bool
    posts: tuple[PostCard, ...]
    posts_count: int
    followers: int
    following: int


def _contains(needle: str, *texts: str) -> bool:
    needle = needle.lower()
    return any(needle in text.lower() for text in texts)


def card(gram: Gram, post_id: str) -> PostCard:
    state = gram.post_states[post_id]
    return PostCard(
        post=gram.posts[post_id],
        likes=likes_now(gram, post_id),
        is_liked=state.is_liked,
        is_saved=state.is_saved,
        comment_count=len(comments_of(gram, post_id)),
    )


@per_state()
def feed(gram: Gram) -> tuple[PostCard, ...]:
    """Every post, newest first."""
    return tuple(card(gram, p.id) for p in newest_first(gram.posts.values()))


@per_state()
def story_bar(gram: Gram) -> tuple[StoryBubble, ...]:
    """One bubble per story still up: not yet watched first, newest first within each (an
    expired story just leaves the tray, as on Instagram)."""
    ordered = newest_first(present(gram.stories.values()))
    viewed = gram.viewed_stories
    return tuple(
        StoryBubble(s, s.id in viewed)
        for s in sorted(ordered, key=lambda s: s.id in viewed)  # stable: keeps newest first
    )


def story_neighbours(gram: Gram, story_id: str) -> tuple[str | None, str | None]:
    """The viewer's previous and next story in the tray as it is now, newest first: next is the
    first later story not yet watched (the bar's point), else simply the next one. A story that
    expired is skipped; one that expired while open still steps on to its neighbours (its
    viewer says it is unavailable, and Instagram's moves on from it)."""
    ordered = [s.id for s in newest_first(gram.stories.values())]
    if story_id not in ordered:
        return (None, None)
    n = ordered.index(story_id)
    up = {s.id for s in present(gram.stories.values())}
    earlier = [i for i in ordered[:n] if i in up]
    later = [i for i in ordered[n + 1 :] if i in up]
    unwatched = [i for i in later if i not in gram.viewed_stories]
    following = unwatched[0] if unwatched else (later[0] if later else None)
    return (earlier[-1] if earlier else None, following)


@per_state()
def explore(gram: Gram, q: str) -> tuple[PostCard, ...]:
    """The Explore grid: every post but the task's target posts (as the original), filtered by
    caption, location or author username."""
    return tuple(
        c
        for c in feed(gram)
        if not c.post.is_target
        and _contains(q, c.post.caption, c.post.location, c.post.author.username)
    )


@per_state()
def search_people(gram: Gram, q: str) -> tuple[Person, ...]:
    """Members whose username or name contains the search (the self user left out)."""
    if not q:
        return ()
    found = (
        p
        for p in MEMBERS.everyone(gram.catalog).values()
        if p.id != gram.me.id and p.id in known_people(gram) and _contains(q, p.username, p.name)
    )
    return tuple(found)[:SEARCH_RESULTS]


@per_state()
def suggestions(gram: Gram) -> tuple[Person, ...]:
    """Authors in the feed the self user does not follow yet, most posts first."""
    authors = [
        post.author
        for post in gram.posts.values()
        if post.author.id != gram.me.id and not is_following(gram, post.author.id)
    ]
    by_id = {author.id: author for author in authors}
    ranked = Counter(author.id for author in authors).most_common(SUGGESTIONS_SHOWN)
    return tuple(by_id[user_id] for user_id, _ in ranked)


def preview(gram: Gram, conversation: Conversation) -> str:
    """The row's preview: the self user's last reply, else the catalog's `lastMessage` (which
    need not be the thread's most telling message — the original's, kept on purpose)."""
    mine = [m for m in gram.sent if m.conversation_id == conversation.id]
    if not mine:
        return conversation.last_message or "Say hi"
    return "You sent a post" if mine[-1].post_id else f"You: {mine[-1].text}"


@per_state()
def inbox(gram: Gram) -> tuple[ThreadRow, ...]:
    """DM threads, the most recently active first."""
    rows = []
    for c in gram.conversations.values():
        sent_at = [m.at for m in gram.sent if m.conversation_id == c.id]
        rows.append(
            ThreadRow(c, preview(gram, c), unread_in(gram, c.id), max([c.arrived_at, *sent_at]))
        )
    return tuple(sorted(rows, key=lambda r: (-r.at, -r.conversation.order)))


@per_state()
def thread(gram: Gram, conversation_id: str) -> tuple[Bubble, ...]:
    """The thread's catalog messages, then what the self user sent (notes and shared posts)."""
    conversation = gram.conversations[conversation_id]
    received = tuple(
        Bubble(m.sender.id == gram.me.id, m.sender, m.text, None) for m in conversation.messages
    )
    sent = tuple(
        Bubble(True, gram.me, m.text, gram.posts.get(m.post_id or ""))
        for m in gram.sent
        if m.conversation_id == conversation_id
    )
    return received + sent


@per_state()
def activity(gram: Gram) -> tuple[ActivityRow, ...]:
    """Activity items, newest first."""
    return tuple(
        ActivityRow(
            item=a,
            unread=not gram.read_activity[a.id],
            post=gram.posts.get(a.target_post_id or ""),
            follows_back=is_following(gram, a.actor.id),
        )
        for a in newest_first(gram.activity.values())
    )


@per_state()
def badges(gram: Gram) -> Badges:
    return Badges(unread_activity_count(gram), unread_conversation_count(gram))


@per_state()
def profile(gram: Gram, user_id: str, tab: str) -> ProfileView:
    """A member's profile. Posts: those of theirs in the feed (saved ones on the self user's
    Saved tab). Counts: the catalog's, never fewer than the posts shown; following the person
    adds one follower, and the self user's own following grows with each follow."""
    is_self = user_id == gram.me.id
    who = gram.me if is_self else person(gram.catalog, user_id)
    theirs = tuple(c for c in feed(gram) if c.post.author.id == user_id)
    saved = tuple(c for c in feed(gram) if c.is_saved) if is_self else ()
    shown = {"posts": theirs, "saved": saved}.get(tab, ())  # Tagged: nobody tags anyone here
    followed = is_following(gram, user_id)
    return ProfileView(
        person=who,
        is_self=is_self,
        followed=followed,
        posts=shown,
        posts_count=max(who.posts_count, len(theirs)),
        followers=who.followers + int(followed),
        following=who.following + (len(gram.followed) if is_self else 0),
    )


@per_state()
def following(gram: Gram) -> tuple[Person, ...]:
    return tuple(person(gram.catalog, u) for u in reversed(gram.followed))
