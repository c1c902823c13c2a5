"""What each MicroDin screen shows: pure functions of (network, URL state), memoised per state.

Templates only lay these out, and tests can check a screen without HTML. Lists are newest
first (the original listed posts and jobs in arrival order, so new ones sank to the bottom and
jobs past the fifth were hidden: both fixed here).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from itertools import islice
from typing import Any

from apps.kit.derived import per_state
from apps.kit.feeds import likes_now, thread_with
from apps.microdin import catalog as records
from apps.microdin import state as net
from apps.microdin.query import JobsQuery, MessagingQuery, NotificationsQuery, SearchQuery
from apps.microdin.state import (
    ENVIRONMENT,
    Comment,
    Company,
    Connection,
    Conversation,
    Job,
    Message,
    Network,
    Notification,
    Person,
    Post,
    ProfileSection,
)

INVITATIONS_PREVIEW = 3
SUGGESTIONS = 8
SEARCH_LIMITS = {"people": 5, "companies": 5, "jobs": 3}
NOTIFICATION_KINDS = {"posts": ("like", "comment"), "mentions": ("mention",), "jobs": ("job",)}


@dataclass(frozen=True)
class NavBadges:
    network: int  # pending invitations
    messaging: int  # unread messages
    notifications: int  # unread notifications


@dataclass(frozen=True)
class PostCard:
    post: Post
    likes: int
    is_liked: bool
    comments: tuple[Comment, ...]


@dataclass(frozen=True)
class JobCard:
    job: Job
    is_applied: bool
    opened: bool


@dataclass(frozen=True)
class ThreadRow:
    conversation: Conversation
    unread: int
    last: Message | None

    @property
    def last_at(self) -> float:
        return self.last.sent_at if self.last else 0


@dataclass(frozen=True)
class NotificationRow:
    notification: Notification
    is_read: bool
    target: str  # where clicking it goes, relative to the environment root


def _contains(needle: str, *texts: str) -> bool:
    needle = needle.strip().casefold()
    return not needle or any(needle in text.casefold() for text in texts)


@per_state()
def nav_badges(network: Network) -> NavBadges:
    return NavBadges(
        network=net.pending_connection_count(network),
        messaging=net.unread_message_count(network),
        notifications=net.unread_notification_count(network),
    )


def post_card(network: Network, post_id: str) -> PostCard:
    return PostCard(
        post=network.posts[post_id],
        likes=likes_now(network, post_id),
        is_liked=network.post_states[post_id].is_liked,
        comments=net.all_comments(network, post_id),
    )


@per_state()
def feed(network: Network) -> tuple[PostCard, ...]:
    posts = net.newest_first(network.posts.values(), "posted_at")
    return tuple(post_card(network, post.id) for post in posts)


def news(catalog: Any) -> tuple[Mapping[str, Any], ...]:
    """The right column's headlines (our catalog's `news` table; none in the original's)."""
    return tuple(catalog.table(ENVIRONMENT, "news").values())


@per_state()
def feed_suggestions(network: Network) -> tuple[Company, ...]:
    """ "Add to your feed": companies of the catalog other than the self user's (first three)."""
    mine = network.me.company.id if network.me.company else None
    companies = (
        records.company(network.catalog, entity_id)
        for entity_id, entity in network.catalog.entities.items()
        if entity.get("type") == "company" and entity_id != mine
    )
    return tuple(islice(companies, 3))


# --- my network -------------------------------------------------------------------------------


@per_state()
def invitations(network: Network) -> tuple[Connection, ...]:
    """Invitations waiting for an answer, newest first."""
    pending = (c for c in network.connections.values() if net.status(network, c.id) == "pending")
    return tuple(net.newest_first(pending, "received_at"))


@per_state()
def suggestions(network: Network) -> tuple[Person, ...]:
    """People you may know: members not connected and with no invitation on the screen."""
    known = {c.person.id for c in network.connections.values()}
    known |= set(network.stats.connected_ids) | {network.me.id}
    people = records.MEMBERS.everyone(network.catalog)
    return tuple(p for i, p in people.items() if i not in known)[:SUGGESTIONS]


@per_state()
def connected_people(network: Network) -> tuple[Person, ...]:
    accepted = [
        c.person
        for c in net.newest_first(network.connections.values(), "received_at")
        if net.status(network, c.id) == "accepted"
    ]
    already = [records.person(network.catalog, i) for i in network.stats.connected_ids]
    return tuple(accepted + already)


# --- jobs ---------------------------------------------------------------------------------------


@dataclass(frozen=True)
class JobsScreen:
    query: JobsQuery
    cards: tuple[JobCard, ...]
    opened: JobCard | None
    total: int


def job_card(network: Network, job: Job, opened: bool) -> JobCard:
    return JobCard(job, network.job_states[job.id].is_applied, opened)


@per_state()
def jobs_screen(network: Network, query: JobsQuery) -> JobsScreen:
    """The job list (title, company, location only) and the open posting with its requirements.
    `query.job` must be on the network (the view checks)."""
    cards = tuple(
        job_card(network, job, job.id == query.job)
        for job in net.newest_first(network.jobs.values(), "posted_at")
        if (query.filter != "applied" or network.job_states[job.id].is_applied)
        and _contains(query.q, job.title, job.company.name, job.location)
    )
    opened = job_card(network, network.jobs[query.job], True) if query.job else None
    return JobsScreen(query, cards, opened, len(network.jobs))


# --- messaging -----------------------------------------------------------------------------------


@dataclass(frozen=True)
class MessagingScreen:
    query: MessagingQuery
    rows: tuple[ThreadRow, ...]
    opened: Conversation | None
    thread: tuple[Message, ...]


def thread_rows(network: Network) -> list[ThreadRow]:
    rows = []
    for conversation in network.conversations.values():
        messages = net.conversation_messages(network, conversation.id)
        last = messages[-1] if messages else None
        rows.append(ThreadRow(conversation, net.unread_in(network, conversation.id), last))
    # Latest activity first; a thread without messages yet (just started) goes on top.
    return sorted(rows, key=lambda r: (r.last is not None, -r.last_at, r.conversation.order))


@per_state()
def messaging_screen(network: Network, query: MessagingQuery) -> MessagingScreen:
    rows = tuple(
        r
        for r in thread_rows(network)
        if (query.filter != "unread" or r.unread or r.conversation.id == query.conversation)
        and _contains(query.q, r.conversation.other.name, r.last.content if r.last else "")
    )
    opened = network.conversations.get(query.conversation or "")
    thread = tuple(net.conversation_messages(network, opened.id)) if opened else ()
    return MessagingScreen(query, rows, opened, thread)


# --- notifications ------------------------------------------------------------------------------


def notification_target(network: Network, notification: Notification) -> str:
    """Where clicking goes: the post for a like, comment or mention of one, invitations for a
    connection, the thread for a message, jobs for a job, the person otherwise."""
    kind = notification.type
    if kind in ("like", "comment", "mention"):
        post_id = notification.target_post_id
        return f"feed/update/{post_id}/" if post_id in network.posts else ""
    if kind == "connection":
        return "mynetwork/"
    if kind == "message":
        return "messaging/"
    if kind == "job":
        return "jobs/"
    return f"in/{notification.actor.id}/"


@per_state()
def notifications_screen(
    network: Network, query: NotificationsQuery
) -> tuple[NotificationRow, ...]:
    kinds = NOTIFICATION_KINDS.get(query.filter)
    rows = (
        NotificationRow(
            n, network.notification_states[n.id].is_read, notification_target(network, n)
        )
        for n in net.newest_first(network.notifications.values(), "at")
        if kinds is None or n.type in kinds
    )
    return tuple(r for r in rows if not (query.filter == "unread" and r.is_read))


# --- profile, company, search --------------------------------------------------------------------


@dataclass(frozen=True)
class Profile:
    person: Person
    is_self: bool
    about: str
    skills: tuple[str, ...]
    education: tuple[Mapping[str, str], ...]
    connections: int
    profile_views: int
    sections: tuple[ProfileSection, ...]
    conversation_id: str | None  # the thread with this person, if any


def profile(network: Network, user_id: str) -> Profile | None:
    catalog = network.catalog
    user = catalog.users.get(user_id)
    if user is None:
        return None
    record = records.MEMBERS.profile(catalog, user_id)
    is_self = user_id == network.me.id
    scholar = (user.get("microscholar") or {}).get("affiliation")
    education = tuple(record.get("education") or ()) or (
        ({"school": scholar, "degree": ""},) if scholar else ()
    )
    return Profile(
        person=records.person(catalog, user_id),
        is_self=is_self,
        about=str(user.get("bio") or ""),
        skills=tuple(record.get("skills") or user.get("interests") or ()),
        education=education,
        connections=net.connections_count(network)
        if is_self
        else int(record.get("connections") or 0),
        profile_views=network.stats.profile_views
        if is_self
        else int(record.get("profileViews") or 0),
        sections=network.sections if is_self else (),
        conversation_id=thread_with(network, user_id),
    )


@dataclass(frozen=True)
class CompanyPage:
    company: Company
    jobs: tuple[JobCard, ...]
    people: tuple[Person, ...]


def company_page(network: Network, company_id: str) -> CompanyPage | None:
    jobs = [j for j in network.jobs.values() if j.company.id == company_id]
    if company_id in network.catalog.entities:
        company = records.company(network.catalog, company_id)
    elif jobs:  # known only from its postings
        company = jobs[0].company
    else:
        return None
    cards = tuple(job_card(network, job, False) for job in net.newest_first(jobs, "posted_at"))
    people = tuple(
        p
        for p in records.MEMBERS.everyone(network.catalog).values()
        if p.company and p.company.id == company_id
    )
    return CompanyPage(company, cards, people)


@dataclass(frozen=True)
class SearchResults:
    query: SearchQuery
    people: tuple[Person, ...]
    companies: tuple[Company, ...]
    jobs: tuple[Job, ...]


@per_state()
def search(network: Network, query: SearchQuery) -> SearchResults:
    if not query.q:
        return SearchResults(query, (), (), ())
    people = tuple(
        p
        for p in records.MEMBERS.everyone(network.catalog).values()
        if _contains(query.q, p.name, p.title, p.company.name if p.company else "")
    )
    companies = tuple(
        records.company(network.catalog, i)
        for i, e in network.catalog.entities.items()
        if e.get("type") == "company" and _contains(query.q, str(e.get("name", "")))
    )
    jobs = tuple(
        job
        for job in net.newest_first(network.jobs.values(), "posted_at")
        if _contains(query.q, job.title, job.company.name)
    )
    found = {"people": people, "companies": companies, "jobs": jobs}
    if query.kind != "all":  # one kind, all of it
        return SearchResults(query, **{k: v if k == query.kind else () for k, v in found.items()})
    return SearchResults(query, **{k: v[: SEARCH_LIMITS[k]] for k, v in found.items()})
