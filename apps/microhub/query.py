"""The list screens' URL state: `issues/?state=closed&q=sync&sort=oldest`, `pulls/?state=closed`,
`actions/?workflow=wf-ci` — each a stable, canonical URL (defaults left out)."""

from __future__ import annotations

from dataclasses import dataclass

from apps.kit.query import InvalidQuery, QueryState, choice, text

__all__ = ["ActionsQuery", "InvalidQuery", "IssuesQuery", "PullsQuery"]

SORTS = ("newest", "oldest", "comments")


@dataclass(frozen=True)
class IssuesQuery(QueryState):
    state: str = choice(("open", "closed"), default="open")
    q: str = text()
    sort: str = choice(SORTS, default="newest")


@dataclass(frozen=True)
class PullsQuery(QueryState):
    state: str = choice(("open", "closed"), default="open")


@dataclass(frozen=True)
class ActionsQuery(QueryState):
    workflow: str = text()
