"""What each MicroChat screen shows for a URL: pure functions of (chat, query, root), memoised
per state. Times stay simulated seconds; the template tags put them in words against the page's
clock (templatetags/microchat.py)."""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass
from datetime import date

from apps.kit.derived import per_state
from apps.kit.retractions import present
from apps.microchat import state as chats
from apps.microchat.calendar import working_day
from apps.microchat.query import CallsQuery, ChatQuery
from apps.microchat.state import Call, Chat, Conversation, Message, Team

FILTER_LABELS = {"unread": "Unread", "chats": "Chats", "meetings": "Meeting chats"}
PREVIEW_LENGTH = 90
DELETED = "This message has been deleted."  # what Teams shows in place of a deleted message
RUN_GAP_S = 5 * 60  # a sender's messages closer than this share one header (a "run")
SPEED_DIAL = 8
MEMBERS_SHOWN = 10
SEARCH_LIMIT = 50


# --- the chat list ---------------------------------------------------------------------------


@dataclass(frozen=True)
class ConversationRow:
    conversation: Conversation
    people: tuple[str, ...]  # names for the avatar: the other person, or up to four members
    preview: str  # the last message, "You: " before your own
    last_at: float | None
    unread: int
    pinned: bool
    muted: bool
    url: str
    current: bool


@dataclass(frozen=True)
class FilterPill:
    name: str
    label: str
    url: str
    current: bool


@dataclass(frozen=True)
class ChatList:
    pills: tuple[FilterPill, ...]
    favorites: tuple[ConversationRow, ...]
    others: tuple[ConversationRow, ...]
    empty_text: str


@per_state()
def conversation_messages(chat: Chat) -> dict[str, tuple[str, ...]]:
    """Each conversation's message ids by time sent, then delivery (a stable sort keeps it)."""
    grouped: dict[str, list[str]] = {}
    for message_id, message in chat.messages.items():
        grouped.setdefault(message.conversation_id, []).append(message_id)
    return {
        conversation_id: tuple(sorted(ids, key=lambda i: chat.messages[i].sent_at))
        for conversation_id, ids in grouped.items()
    }


@per_state()
def unread_counts(chat: Chat) -> dict[str, int]:
    return dict(Counter(chat.messages[i].conversation_id for i in chats.unread_ids(chat)))


def chat_url(root: str, filter: str = "all", conversation_id: str | None = None) -> str:
    query = ChatQuery(filter=filter)
    if conversation_id is None:
        return root + query.querystring()
    return root + query.with_item("conversation", conversation_id)


def people_of(chat: Chat, conversation: Conversation) -> tuple[str, ...]:
    others = [p for p in conversation.participant_ids if p != chat.self_id]
    if conversation.type == "direct":
        return (conversation.name,)
    return tuple(chat.user_name(p) for p in others[:4])


def preview_of(message: Message | None) -> str:
    if message is None:
        return "No messages yet"
    if message.gone_at is not None:
        return DELETED
    text = " ".join(message.content.split()) or (
        "Sent an attachment" if message.has_attachment else ""
    )
    text = text[:PREVIEW_LENGTH]
    return f"You: {text}" if message.by_self else text


def last_message(chat: Chat, conversation_id: str) -> Message | None:
    ids = conversation_messages(chat).get(conversation_id)
    return chat.messages[ids[-1]] if ids else None


def matches_filter(conversation: Conversation, unread: int, name: str) -> bool:
    meeting = conversation.type == "meeting"
    return {"unread": unread > 0, "chats": not meeting, "meetings": meeting}.get(name, True)


@per_state()
def chat_list(chat: Chat, query: ChatQuery, root: str) -> ChatList:
    """Favorites then Chats; each sorted by newest message, chats without messages last.
    The open chat stays listed under a filter it no longer matches (opening an unread chat
    under "Unread" must not make it vanish under the cursor)."""
    counts = unread_counts(chat)
    rows = []
    for conversation in chat.conversations.values():
        unread = counts.get(conversation.id, 0)
        current = conversation.id == query.conversation
        if not (matches_filter(conversation, unread, query.filter) or current):
            continue
        last = last_message(chat, conversation.id)
        rows.append(
            ConversationRow(
                conversation=conversation,
                people=people_of(chat, conversation),
                preview=preview_of(last),
                last_at=last.sent_at if last else None,
                unread=unread,
                pinned=chat.pinned(conversation.id),
                muted=chat.muted(conversation.id),
                url=chat_url(root, query.filter, conversation.id),
                current=current,
            )
        )
    rows.sort(key=lambda r: (r.last_at is None, -(r.last_at or 0.0), r.conversation.order))
    pills = tuple(
        # A pill toggles: pressing the current one shows every chat again.
        FilterPill(
            name,
            label,
            chat_url(root, "all" if query.filter == name else name, query.conversation),
            query.filter == name,
        )
        for name, label in FILTER_LABELS.items()
    )
    empty = {
        "unread": "You're all caught up: no unread chats.",
        "meetings": "No meeting chats.",
    }.get(query.filter, "No chats yet.")
    return ChatList(
        pills=pills,
        favorites=tuple(r for r in rows if r.pinned),
        others=tuple(r for r in rows if not r.pinned),
        empty_text=empty,
    )


# --- the open conversation ---------------------------------------------------------------------


@dataclass(frozen=True)
class ReplyRef:
    message_id: str
    sender_name: str
    snippet: str


@dataclass(frozen=True)
class ReactionChip:
    reaction: str
    count: int
    mine: bool
    names: str  # who reacted, for the chip's label


@dataclass(frozen=True)
class MessageView:
    message: Message
    is_read: bool
    starts_run: bool  # sender name and time shown above it
    reply: ReplyRef | None
    reactions: tuple[ReactionChip, ...]
    dimmed: bool  # an in-conversation search is on and this message does not match


@dataclass(frozen=True)
class OpenConversation:
    conversation: Conversation
    people: tuple[str, ...]
    member_names: tuple[str, ...]
    pinned: bool
    muted: bool
    messages: tuple[MessageView, ...]
    find: str
    found: int
    replying: ReplyRef | None
    find_url: str  # the same chat without the in-conversation search
    back: str  # query string actions return to


def snippet(message: Message, length: int = 80) -> str:
    text = " ".join(message.content.split())
    return text if len(text) <= length else text[: length - 1] + "…"


def reply_ref(chat: Chat, message_id: str | None) -> ReplyRef | None:
    """The quoted line above a reply; only for a message that has arrived."""
    target = chat.messages.get(message_id) if message_id else None
    if target is None:
        return None
    name = "You" if target.by_self else target.sender_name
    return ReplyRef(target.id, name, snippet(target))


def reaction_chips(chat: Chat, message_id: str) -> tuple[ReactionChip, ...]:
    return tuple(
        ReactionChip(
            reaction, len(users), chat.self_id in users, ", ".join(chat.called(u) for u in users)
        )
        for reaction, users in chat.reactions.get(message_id, ())
    )


def matches_find(message: Message, needle: str) -> bool:
    haystack = (message.content, message.sender_name, *(a.name for a in message.attachments))
    return any(needle in text.casefold() for text in haystack)


@per_state()
def open_conversation(chat: Chat, query: ChatQuery) -> OpenConversation:
    """`query.conversation` must be in the workspace (the view checks)."""
    conversation = chat.conversations[query.conversation]
    needle = query.find.casefold()
    views, previous = [], None
    for message_id in conversation_messages(chat).get(conversation.id, ()):
        message = chat.messages[message_id]
        starts_run = (
            previous is None
            or previous.sender_id != message.sender_id
            or message.sent_at - previous.sent_at > RUN_GAP_S
            or message.reply_to is not None
        )
        views.append(
            MessageView(
                message=message,
                is_read=chat.read[message_id],
                starts_run=starts_run,
                reply=reply_ref(chat, message.reply_to),
                reactions=reaction_chips(chat, message_id),
                dimmed=bool(needle) and not matches_find(message, needle),
            )
        )
        previous = message
    replying = reply_ref(chat, query.reply)
    if replying and chat.messages[replying.message_id].conversation_id != conversation.id:
        replying = None
    return OpenConversation(
        conversation=conversation,
        people=people_of(chat, conversation),
        member_names=tuple(chat.called(p) for p in conversation.participant_ids),
        pinned=chat.pinned(conversation.id),
        muted=chat.muted(conversation.id),
        messages=tuple(views),
        find=query.find,
        found=sum(1 for v in views if not v.dimmed) if needle else 0,
        replying=replying,
        find_url=ChatQuery(filter=query.filter).with_item("conversation", conversation.id),
        back=query.but(reply="").querystring(),
    )


# --- global search -------------------------------------------------------------------------------


@dataclass(frozen=True)
class MessageHit:
    message: Message
    conversation_name: str
    url: str


@dataclass(frozen=True)
class SearchResults:
    q: str
    conversations: tuple[ConversationRow, ...]
    messages: tuple[MessageHit, ...]
    more: int  # message hits beyond the ones shown


@per_state()
def search(chat: Chat, q: str, root: str) -> SearchResults:
    """Chats by name or member, messages by text or sender; newest messages first."""
    needle = q.casefold()
    if not needle:
        return SearchResults(q, (), (), 0)
    listed = chat_list(chat, ChatQuery(), root)
    conversations = tuple(
        row
        for row in (*listed.favorites, *listed.others)
        if needle in row.conversation.name.casefold()
        or any(needle in name.casefold() for name in row.people)
    )
    hits = [
        m
        for m in present(chat.messages.values())  # a deleted message's text is not found
        if needle in m.content.casefold() or needle in m.sender_name.casefold()
    ]
    hits.sort(key=lambda m: m.sent_at, reverse=True)
    shown = tuple(
        MessageHit(
            m,
            getattr(chat.conversations.get(m.conversation_id), "name", ""),
            chat_url(root, conversation_id=m.conversation_id),
        )
        for m in hits[:SEARCH_LIMIT]
    )
    return SearchResults(q, conversations, shown, max(0, len(hits) - SEARCH_LIMIT))


# --- teams -----------------------------------------------------------------------------------------


@dataclass(frozen=True)
class TeamView:
    team: Team
    url: str
    unread: int  # the channels' unread posts (the catalog's numbers)


@dataclass(frozen=True)
class TeamDetail:
    team: Team
    channel_id: str
    member_names: tuple[str, ...]
    more_members: int
    owner_name: str


@per_state()
def team_cards(chat: Chat, root: str) -> tuple[TeamView, ...]:
    teams = sorted(chat.teams.values(), key=lambda t: t.order)
    return tuple(
        TeamView(t, f"{root}teams/{t.id}", sum(c.unread_count for c in t.channels)) for t in teams
    )


def team_detail(chat: Chat, team: Team, channel_id: str) -> TeamDetail:
    return TeamDetail(
        team=team,
        channel_id=channel_id,
        member_names=tuple(chat.called(m) for m in team.member_ids[:MEMBERS_SHOWN]),
        more_members=max(0, len(team.member_ids) - MEMBERS_SHOWN),
        owner_name=chat.user_name(team.owner_id) if team.owner_id else "",
    )


# --- calls and activity -----------------------------------------------------------------------------


@dataclass(frozen=True)
class CallsScreen:
    calls: tuple[Call, ...]
    missed: int
    total: int
    speed_dial: tuple[str, ...]


def newest_calls(chat: Chat) -> list[Call]:
    """Newest first: calls delivered during the run above the log they started with (dated
    from its words); a call whose words give no time last, in the catalog's order."""
    return sorted(chat.calls.values(), key=lambda c: (c.at is None, -(c.at or 0.0), c.order))


@per_state()
def calls_screen(chat: Chat, query: CallsQuery) -> CallsScreen:
    calls = newest_calls(chat)
    by_order = sorted(chat.conversations.values(), key=lambda c: c.order)
    dial = list(dict.fromkeys(c.name for c in by_order if c.type == "direct"))
    return CallsScreen(
        calls=tuple(c for c in calls if query.filter == "all" or c.missed),
        missed=chats.missed_call_count(chat),
        total=len(calls),
        speed_dial=tuple(dial[:SPEED_DIAL]),
    )


@dataclass(frozen=True)
class ActivityItem:
    kind: str  # "missed_call" | "reaction"
    who: str
    text: str
    at: float | None
    time_text: str
    url: str


@per_state()
def activity(chat: Chat, root: str) -> tuple[ActivityItem, ...]:
    """Missed calls and reactions to your messages (mentions stay inside the chats, where the
    original shows them)."""
    items = [
        ActivityItem("missed_call", c.name, "Missed call", c.at, c.time_text, f"{root}calls")
        for c in newest_calls(chat)
        if c.missed
    ]
    items += [
        ActivityItem(
            "reaction",
            chat.user_name(user),
            f"Reacted {reaction} to “{snippet(message, 60)}”",
            message.sent_at,
            "",
            chat_url(root, conversation_id=message.conversation_id),
        )
        for message_id, reactions in chat.reactions.items()
        if (message := chat.messages.get(message_id)) is not None and message.by_self
        for reaction, users in reactions
        for user in users
        if user != chat.self_id
    ]
    items.sort(key=lambda i: i.at if i.at is not None else float("-inf"), reverse=True)
    return tuple(items)


# --- the calendar ------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Meeting:
    day: date
    start: str
    minutes: int
    title: str
    url: str

    @property
    def top(self) -> int:
        """Minutes after 08:00, the first hour the grid shows."""
        hours, minutes = (int(x) for x in self.start.split(":"))
        return (hours - 8) * 60 + minutes


@per_state()
def meetings(chat: Chat, today: date, root: str) -> tuple[Meeting, ...]:
    found = []
    for c in chat.conversations.values():
        if c.type != "meeting" or c.schedule is None:
            continue
        day, start, minutes = c.schedule
        found.append(
            Meeting(
                working_day(today, day),
                start,
                minutes,
                c.name,
                chat_url(root, conversation_id=c.id),
            )
        )
    return tuple(sorted(found, key=lambda m: (m.day, m.start)))


# --- the app rail ---------------------------------------------------------------------------------


@dataclass(frozen=True)
class Rail:
    unread_chats: int  # the Chat icon's badge
    missed_calls: int  # the Activity icon's badge


@per_state()
def rail(chat: Chat) -> Rail:
    return Rail(len(unread_counts(chat)), chats.missed_call_count(chat))
