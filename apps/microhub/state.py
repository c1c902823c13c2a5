"""MicroHub's state: one repository, its issues, pull requests, commits, files and workflow runs,
and what the user did to it. Immutable (frozen dataclasses, MappingProxyType); reducers return
a new `Hub`.

The star count moves between events: it is the `stars` waypoint series read at `now`, plus the
user's own star (`star_offset`), never an event of its own — `star_count(hub, now)` is the one
function the page, the live push, the baselines and the evaluation tables all call.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any

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
    color: str
    description: str = ""


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
    number: int
    title: str
    body: str
    # As created (by the catalog or the user); the current one is in issue_states / pr_states.
    state: str
    author: str  # username
    author_name: str
    opened_at: float
    labels: tuple[Label, ...] = ()
    comments: tuple[Comment, ...] = ()


@dataclass(frozen=True, kw_only=True)
class Issue(Post):
    assignees: tuple[Person, ...] = ()
    user_created: bool = False


@dataclass(frozen=True)
class IssueState:
    state: str = "open"
    viewed: bool = False


@dataclass(frozen=True)
class Check:
    name: str
    status: str  # success · failure · pending


@dataclass(frozen=True, kw_only=True)
class PullRequest(Post):
    source: str
    target: str
    review_status: str
    reviewers: tuple[Person, ...] = ()
    checks: tuple[Check, ...] = ()
    commits: int = 0
    additions: int = 0
    deletions: int = 0
    files_changed: int = 0


@dataclass(frozen=True)
class Commit:
    id: str
    sha: str
    message: str
    author: str
    author_name: str
    at: float
    additions: int = 0
    deletions: int = 0
    files: tuple[str, ...] = ()
    verified: bool = False


@dataclass(frozen=True)
class RepoFile:
    id: str
    name: str
    path: str
    type: str  # file · folder
    parent_id: str | None
    content: str = ""
    size: int = 0
    language: str = ""
    last_commit_sha: str = ""
    last_commit_message: str = ""

    @property
    def is_folder(self) -> bool:
        return self.type in ("folder", "dir")


@dataclass(frozen=True)
class Step:
    name: str
    conclusion: str
    duration: int


@dataclass(frozen=True)
class Job:
    name: str
    status: str
    conclusion: str
    duration: int
    steps: tuple[Step, ...] = ()


@dataclass(frozen=True)
class WorkflowRun:
    id: str
    workflow_id: str
    workflow_name: str
    number: int
    status: str  # completed · in_progress · queued
    conclusion: str  # success · failure · cancelled · "" while running
    branch: str
    commit_sha: str
    commit_message: str
    actor: str
    actor_name: str
    event: str
    duration: int
    at: float
    jobs: tuple[Job, ...] = ()

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
        return self.pr_states.get(pr_id, "open")

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


def open_issue_count(hub: Hub) -> int:
    return sum(1 for i in hub.issue_states.values() if i.state == "open")


def open_pr_count(hub: Hub) -> int:
    return sum(1 for pr_id in hub.prs if hub.pr_state(pr_id) == "open")


def self_comment_count(hub: Hub) -> int:
    return len(hub.user_comments)
