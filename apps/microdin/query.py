"""The screens' URL state: filters, searches and the open item live in the query string.

`/r/<token>/microdin/jobs/?filter=applied&q=python&job=<id>` and the like — every screen is a
stable, shareable URL, canonical (defaults left out).
"""

from __future__ import annotations

from dataclasses import dataclass

from apps.kit.query import QueryState, choice, item, text

NOTIFICATION_FILTERS = ("all", "unread", "posts", "mentions", "jobs")
SEARCH_KINDS = ("all", "people", "companies", "jobs")


@dataclass(frozen=True)
class JobsQuery(QueryState):
    filter: str = choice(("all", "applied"), default="all")
    q: str = text()
    job: str | None = item()


@dataclass(frozen=True)
class MessagingQuery(QueryState):
    filter: str = choice(("all", "unread"), default="all")
    q: str = text()
    conversation: str | None = item()


@dataclass(frozen=True)
class NotificationsQuery(QueryState):
    filter: str = choice(NOTIFICATION_FILTERS, default="all")


@dataclass(frozen=True)
class SearchQuery(QueryState):
    q: str = text()
    kind: str = choice(SEARCH_KINDS, default="all")


def thread_path(conversation_id: str) -> str:
    """The messaging screen with the thread open."""
    return "messaging/" + MessagingQuery(conversation=conversation_id).querystring()


def job_path(job_id: str) -> str:
    """The jobs screen with the posting open."""
    return "jobs/" + JobsQuery(job=job_id).querystring()
