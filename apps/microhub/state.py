"""MicroHub's state: one repository, its issues, pull requests, commits, files and workflow runs,
and what the user did to it. Immutable (frozen dataclasses, MappingProxyType); reducers return
a new `Hub`.

The star count moves between events: it is the `stars` waypoint series read at `now`, plus the
user's own star (`star_offset`), never an event of its own — `star_count(hub, now)` is the one
function the page, the live push, the baselines and the evaluation tables all call.

A record type read from the catalog declares on each field where the record has it
(`from_catalog`, apps.kit.records); catalog.py computes the rest (display names, dates).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any

from apps.kit.records import each, flag, from_catalog, inner, integer, text, text_or, texts
from apps.kit.state import CatalogState, with_items
from apps.kit.streaming import no_items
from apps.kit.waypoints import Waypoints

ENVIRONMENT = "microhub"


MERGE_STRATEGIES = ("merge", "squash", "rebase")
VISIBILITIES = ("public", "private")


@dataclass(frozen=True)
class Person:
    username: str
    name: str  # display name (their avatar is drawn from it, the same in every environment)


@dataclass(frozen=True)
class Label:
    id: str
    name: str
    color: str = from_catalog(text_or("color", "#ededed"))
    description: str = from_catalog(text_or("description"), default="")


@dataclass(frozen=True)
class Comment:
    id: str
    author: str  # username
    author_name: str
    body: str
    at: float  # simulated seconds
    reactions: tuple[tuple[str, int], ...] = ()
    target_type: str = ""  # "issue" / "pr" for the user's own comments
    target_id: str = ""


@dataclass(frozen=True, kw_only=True)
class Post:
    """What an issue and a pull request share: a numbered, titled post and its discussion."""

    id: str
    # A preloaded one keeps its catalog number; the environment numbers one filed during the task.
    number: int = from_catalog(integer("number"))
    title: str = from_catalog(text("title"))
    body: str = from_catalog(text_or("body"))
    # As created (by the catalog or the user); the current one is in issue_states / pr_states.
    state: str = from_catalog(text_or("state", "open"))
    author: str = from_catalog(text("author"))  # username
    author_name: str
    opened_at: float
    labels: tuple[Label, ...] = ()
    comments: tuple[Comment, ...] = ()


@dataclass(frozen=True, kw_only=True)
class Issue(Post):
    assignees: tuple[Person, ...] = ()


@dataclass(frozen=True)
class IssueState:
    state: str = "open"
    viewed: bool = False


@dataclass(frozen=True)
class Check:
    name: str = from_catalog(text("name"))
    status: str = from_catalog(text("status"))  # success · failure · pending


@dataclass(frozen=True, kw_only=True)
class PullRequest(Post):
    source: str = from_catalog(text("sourceBranch"))
    target: str = from_catalog(text("targetBranch", "main"))
    review_status: str = from_catalog(text_or("reviewStatus", "review-required"))
    reviewers: tuple[Person, ...] = ()
    checks: tuple[Check, ...] = from_catalog(each("checks", Check), default=())
    commits: int = from_catalog(integer("commits"), default=0)
    additions: int = from_catalog(integer("additions"), default=0)
    deletions: int = from_catalog(integer("deletions"), default=0)
    files_changed: int = from_catalog(integer("filesChanged"), default=0)
    gone_at: float | None = None  # closed by someone else then (apps.kit.retractions)


@dataclass(frozen=True)
class Commit:
    id: str
    sha: str = from_catalog(text("sha"))
    message: str = from_catalog(text("message"))
    author: str = from_catalog(text("author"))
    author_name: str
    at: float
    additions: int = from_catalog(integer("additions"), default=0)
    deletions: int = from_catalog(integer("deletions"), default=0)
    files: tuple[str, ...] = from_catalog(texts("filesChanged"), default=())
    verified: bool = from_catalog(flag("verified"), default=False)


@dataclass(frozen=True)
class RepoFile:
    id: str
    name: str = from_catalog(text("name"))
    path: str = from_catalog(text("path"))
    type: str = from_catalog(text_or("type", "file"))  # file · folder
    parent_id: str | None = from_catalog(lambda r: r.get("parentId"))
    content: str = from_catalog(text_or("content"), default="")
    size: int = from_catalog(
        lambda r: int(r.get("size") or len(str(r.get("content") or "").encode())), default=0
    )
    language: str = from_catalog(text_or("language"), default="")
    last_commit_sha: str = from_catalog(inner("lastCommit", "sha"), default="")
    last_commit_message: str = from_catalog(inner("lastCommit", "message"), default="")

    @property
    def is_folder(self) -> bool:
        return self.type in ("folder", "dir")


@dataclass(frozen=True)
class Step:
    name: str = from_catalog(text("name"))
    # its conclusion, or its status while it has none
    conclusion: str = from_catalog(lambda s: str(s.get("conclusion") or s.get("status") or ""))
    duration: int = from_catalog(integer("duration"))


@dataclass(frozen=True)
class Job:
    name: str = from_catalog(text("name"))
    status: str = from_catalog(text("status"))
    conclusion: str = from_catalog(text_or("conclusion"))
    duration: int = from_catalog(integer("duration"))
    steps: tuple[Step, ...] = from_catalog(each("steps", Step), default=())


@dataclass(frozen=True)
class WorkflowRun:
    id: str
    workflow_id: str = from_catalog(text("workflowId"))
    workflow_name: str = from_catalog(text("workflowName"))
    number: int = from_catalog(integer("runNumber"))
    status: str = from_catalog(text_or("status", "completed"))  # completed · in_progress · queued
    # success · failure · cancelled · "" while running
    conclusion: str = from_catalog(text_or("conclusion"))
    branch: str = from_catalog(text("branch"))
    commit_sha: str = from_catalog(inner("commit", "sha"))
    commit_message: str = from_catalog(inner("commit", "message"))
    actor: str = from_catalog(text("actor"))
    actor_name: str
    event: str = from_catalog(text("event"))
    duration: int = from_catalog(integer("duration"))
    at: float
    jobs: tuple[Job, ...] = from_catalog(each("jobs", Job), default=())

    @property
    def outcome(self) -> str:
        """What the status icon shows: the conclusion, or the status while it has none."""
        return self.conclusion or self.status


@dataclass(frozen=True)
class UserRepo:
    id: str
    name: str
    description: str
    visibility: str
    owner: str
    created_at: float
    commits: int = 0


@dataclass(frozen=True)
class Hub(CatalogState):
    # Who the user is comes from the catalog too: an input, not state.
    self_username: str = field(compare=False, repr=False)
    self_name: str = field(compare=False, repr=False)
    repo: Mapping[str, Any]  # the repository record (after preload overrides / settings)
    stars: Waypoints
    forks: int = 0
    watchers: int = 0
    star_offset: int = 0
    starred: bool = False
    watched: bool = False
    forked: bool = False
    preloaded: bool = False
    issues: Mapping[str, Issue] = no_items()  # catalog-derived, in arrival order
    user_issues: Mapping[str, Issue] = no_items()
    issue_states: Mapping[str, IssueState] = no_items()  # catalog and user issues
    prs: Mapping[str, PullRequest] = no_items()
    pr_states: Mapping[str, str] = no_items()
    merged: tuple[str, ...] = ()
    commits: Mapping[str, Commit] = no_items()
    commit_total: int = 0  # the repository's commit count ("2,186 commits")
    runs: Mapping[str, WorkflowRun] = no_items()
    files: Mapping[str, RepoFile] = no_items()
    # Tables the pages show little of and eval_sql may read as (id, JSON): workflows, labels…
    records: Mapping[str, Mapping[str, Mapping[str, Any]]] = no_items()
    user_comments: tuple[Comment, ...] = ()
    following: tuple[str, ...] = ()
    user_repos: tuple[UserRepo, ...] = ()

    def issue(self, issue_id: str) -> Issue | None:
        return self.issues.get(issue_id) or self.user_issues.get(issue_id)

    def issue_state(self, issue_id: str) -> str:
        return self.issue_states.get(issue_id, IssueState()).state

    def pr_state(self, pr_id: str) -> str:
        """The user's merge stands; else a pull request someone else closed shows closed."""
        state = self.pr_states.get(pr_id, "open")
        pr = self.prs.get(pr_id)
        return "closed" if state == "open" and pr is not None and pr.gone_at is not None else state

    @property
    def owner(self) -> str:
        return str(self.repo.get("owner", ""))

    @property
    def name(self) -> str:
        return str(self.repo.get("name", ""))

    @property
    def visibility(self) -> str:
        if "visibility" in self.repo:
            return str(self.repo["visibility"])
        return "private" if self.repo.get("isPrivate") else "public"


def star_count(hub: Hub, now: float) -> int:
    """The stars shown and graded at `now`: the waypoint curve plus the user's own star, rounded
    as the original did (Python's round), never below zero."""
    return max(0, round(hub.stars.value_at(now) + hub.star_offset))


def stars_change_at(hub: Hub, now: float) -> float | None:
    """When the shown star count may next change (it is shown to the unit)."""
    return hub.stars.next_change(now, step=1)


def with_issue_state(hub: Hub, issue_id: str, **changes: Any) -> Hub:
    current = hub.issue_states.get(issue_id, IssueState())
    return with_items(hub, "issue_states", [(issue_id, replace(current, **changes))])


def next_issue_number(hub: Hub) -> int:
    """The original's rule: one more than every loaded and user-created issue's number."""
    numbers = [i.number for i in hub.issues.values()] + [i.number for i in hub.user_issues.values()]
    return max(numbers, default=0) + 1


def next_pr_number(hub: Hub) -> int:
    """Pull requests share numbers with issues: one more than every issue and pull request."""
    return max([next_issue_number(hub), *(pr.number + 1 for pr in hub.prs.values())])
