"""MicroHub's registration with the core: scenario events, baselines, evaluation tables.

Scenario events (the original's, plus three of our own that the paper's MicroHub injects):
- `preload_repo {issue_ids, pr_ids, commit_ids, run_ids, file_ids, …, star_waypoints,
  initial_stars, initial_forks, initial_watchers, initial_commits, default_branch,
  preload_age_offset_ms}` — the repository as the task starts; every id list defaults to ["*"].
- `new_issue {issue_id}` — filed now, numbered after every issue so far (the original's rule).
- `stars_waypoint {stars | delta}` — a point on the star curve at the event's own time: a step
  there (it exists only once fired), then the ramp toward any later preloaded waypoint.
- `new_pull_request {pr_id}`, `new_commit {commit_id}`, `new_workflow_run {run_id}` (ours).
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable, Mapping
from dataclasses import replace
from types import MappingProxyType
from typing import Annotated, Any

from pydantic import Field, model_validator

from apps.kit.arrivals import Deliver, Delivery, Stamp, arrival, event_types
from apps.kit.state import EMPTY
from apps.kit.tables import KEY, Keyed, Table, named, tables
from apps.kit.waypoints import Waypoints
from apps.microhub import catalog as records
from apps.microhub.actions import ACTIONS
from apps.microhub.bench import sample_pages
from apps.microhub.state import (
    ENVIRONMENT,
    Hub,
    IssueState,
    PullRequest,
    next_issue_number,
    next_pr_number,
    self_comment_count,
    star_count,
)
from events.registry import Environment, EventType, ImplicitAction, LoggedEvent, counted
from events.schemas import Payload

WILDCARD = ["*"]
IdList = list[str]


def empty_hub(catalog: Any) -> Hub:
    """Before the preload: the catalog's repository with nothing in it yet."""
    repo = records.repository_record(catalog)
    me = catalog.self_user or {}
    return Hub(
        catalog=catalog,
        self_username=str(me.get("username") or "me"),
        self_name=str(me.get("name") or me.get("username") or "me"),
        repo=MappingProxyType(dict(repo)),
        stars=Waypoints(float(repo.get("stars") or 0)),
        forks=int(repo.get("forks") or 0),
        watchers=int(repo.get("watchers") or 0),
        commit_total=int(repo.get("commits") or 0),
    )


# --- catalog items arriving: preloaded (dated by their catalog order), or during the task ------


def make_issue(hub: Hub, issue_id: str, stamp: Stamp) -> tuple[Any, IssueState] | None:
    """A preloaded issue keeps its catalog number; one filed during the task is numbered after
    every issue so far, so it sorts to the top (the original's rule)."""
    number = None if stamp.preloaded else next_issue_number(hub)
    issue = records.catalog_issue(hub.catalog, issue_id, stamp, number=number)
    return None if issue is None else (issue, IssueState(state=issue.state))


def make_pr(hub: Hub, pr_id: str, stamp: Stamp) -> tuple[PullRequest, str] | None:
    """Numbered after every issue and pull request so far when opened during the task."""
    number = None if stamp.preloaded else next_pr_number(hub)
    pr = records.catalog_pr(hub.catalog, pr_id, stamp, number=number)
    if pr is None:
        return None
    return pr, "merged" if pr_id in hub.merged else pr.state


deliver_issues = Delivery("issues", make_issue, states="issue_states")
deliver_prs = Delivery("prs", make_pr, states="pr_states")
deliver_commits = Delivery(
    "commits", lambda hub, i, stamp: records.catalog_commit(hub.catalog, i, stamp)
)
deliver_runs = Delivery("runs", lambda hub, i, stamp: records.catalog_run(hub.catalog, i, stamp))
deliver_files = Delivery("files", lambda hub, i, stamp: records.catalog_file(hub.catalog, i))


def newest_first(delivery: Delivery[Hub]) -> Deliver[Hub]:
    """`delivery` into a list the newest item heads (a pushed commit, a run just started): what
    arrives goes before what is there, as the original's lists had it."""

    def deliver(hub: Hub, ids: Iterable[str], at: float, *, preloaded: bool) -> Hub:
        delivered = delivery(hub, ids, at, preloaded=preloaded)
        there, now = getattr(hub, delivery.items), getattr(delivered, delivery.items)
        arrived = {key: item for key, item in now.items() if key not in there}
        if not arrived:
            return hub
        return replace(delivered, **{delivery.items: MappingProxyType({**arrived, **there})})

    return deliver


def push_commits(hub: Hub, ids: Iterable[str], at: float, *, preloaded: bool) -> Hub:
    """Pushed now: first in the history, and one more each in the repository's commit count."""
    pushed = newest_first(deliver_commits)(hub, ids, at, preloaded=preloaded)
    added = len(pushed.commits) - len(hub.commits)
    return replace(pushed, commit_total=hub.commit_total + added) if added else hub


# --- preload_repo -----------------------------------------------------------------------------


class PreloadRepo(Payload):
    # Written out rather than generated by `arrivals.preload`: every id list here defaults to
    # every row (["*"]), where a generated preload defaults to none.
    issue_ids: IdList = Field(default=WILDCARD, description='catalog issue ids; ["*"] = all')
    pr_ids: IdList = Field(default=WILDCARD, description='catalog pull request ids; ["*"] = all')
    commit_ids: IdList = Field(default=WILDCARD, description='catalog commit ids; ["*"] = all')
    run_ids: IdList = Field(default=WILDCARD, description='workflow run ids; ["*"] = all')
    file_ids: IdList = WILDCARD
    workflow_ids: IdList = WILDCARD
    label_ids: IdList = WILDCARD
    wiki_ids: IdList = WILDCARD
    project_ids: IdList = WILDCARD
    activity_ids: IdList = WILDCARD
    insight_ids: IdList = WILDCARD
    release_ids: IdList = WILDCARD
    security_ids: IdList = WILDCARD
    scanning_ids: IdList = WILDCARD
    deployment_ids: IdList = WILDCARD
    package_ids: IdList = WILDCARD
    star_waypoints: list[Annotated[list[float], Field(min_length=2, max_length=2)]] = Field(
        default=[], description="[[time, stars], …]: the star curve, known from the start"
    )
    initial_stars: int | None = Field(None, ge=0)
    initial_forks: int | None = Field(None, ge=0)
    initial_watchers: int | None = Field(None, ge=0)
    initial_commits: int | None = Field(None, ge=0)
    default_branch: str | None = None
    preload_age_offset_ms: float = Field(0, ge=0, description="preloaded rows this much older")
    load_all: bool | None = Field(None, description="the original's dev preload flag (all rows)")


# payload id list → (catalog table, delivery), in the order they load.
LOADED: Mapping[str, tuple[str, Deliver[Hub]]] = {
    "issue_ids": ("issues", deliver_issues),
    "pr_ids": ("prs", deliver_prs),
    "commit_ids": ("commits", deliver_commits),
    "run_ids": ("workflow-runs", deliver_runs),
    "file_ids": ("files", deliver_files),
}


def _ids(hub: Hub, payload: Mapping[str, Any], table: str, key: str) -> list[str]:
    return hub.catalog.expand(ENVIRONMENT, table, payload.get(key, WILDCARD))


def _preloaded_repo(hub: Hub, p: Mapping[str, Any]) -> Mapping[str, Any]:
    repo = dict(records.repository_record(hub.catalog))  # a copy: the catalog stays as it is
    if p.get("initial_stars") is not None:
        repo["stars"] = p["initial_stars"]
    if p.get("initial_forks") is not None:
        repo["forks"] = p["initial_forks"]
    if p.get("initial_watchers") is not None:
        repo["watchers"] = p["initial_watchers"]
    if p.get("initial_commits") is not None:
        repo["commits"] = p["initial_commits"]
    if p.get("default_branch"):
        repo["defaultBranch"] = p["default_branch"]
        branches = list(repo.get("branches") or [])
        if p["default_branch"] not in branches:
            repo["branches"] = [p["default_branch"], *branches]
    return MappingProxyType(repo)


def reduce_preload_repo(hub: Hub, event: LoggedEvent) -> Hub:
    """The repository as the task starts, in place of what an earlier preload loaded (the user's
    own issues stay); the core measures the baselines right after."""
    p, catalog = event.payload, hub.catalog
    # Rows are dated from the preload, older by the offset: delivered "at" that start.
    start = event.at - float(p.get("preload_age_offset_ms") or 0) / 1000.0
    own_states = {i: s for i, s in hub.issue_states.items() if i in hub.user_issues}
    hub = replace(
        hub,
        issues=EMPTY,
        issue_states=MappingProxyType(own_states),
        prs=EMPTY,
        pr_states=EMPTY,
        commits=EMPTY,
        runs=EMPTY,
        files=EMPTY,
    )
    for key, (table, deliver) in LOADED.items():
        hub = deliver(hub, _ids(hub, p, table, key), start, preloaded=True)
    passed = {
        table: MappingProxyType(
            {
                i: records.table(catalog, table)[i]
                for i in _ids(hub, p, table, key)
                if i in records.table(catalog, table)
            }
        )
        for table, key in records.PASS_THROUGH.items()
    }
    repo = _preloaded_repo(hub, p)
    stars = Waypoints(float(repo.get("stars") or 0)).with_points(
        (at, value) for at, value in p.get("star_waypoints") or ()
    )
    return replace(
        hub,
        repo=repo,
        stars=stars,
        forks=int(repo.get("forks") or 0) + (1 if hub.forked else 0),
        watchers=int(repo.get("watchers") or 0) + (1 if hub.watched else 0),
        commit_total=int(repo.get("commits") or 0),
        preloaded=True,
        records=MappingProxyType(passed),
    )


# --- stars_waypoint -------------------------------------------------------------------------------


class StarsWaypoint(Payload):
    stars: float | None = Field(None, ge=0, description="the star count at this moment")
    delta: float | None = Field(None, description="stars gained (or lost) at this moment")

    @model_validator(mode="after")
    def one_of(self) -> StarsWaypoint:
        if (self.stars is None) == (self.delta is None):
            raise ValueError("give exactly one of 'stars' and 'delta'")
        return self


def reduce_stars_waypoint(hub: Hub, event: LoggedEvent) -> Hub:
    """A point at the event's own time: `stars`, or the curve's value there plus `delta`
    (never below zero). The user's own star rides on top and is not part of the curve."""
    p = event.payload
    if p.get("stars") is not None:
        value = float(p["stars"])
    else:
        value = max(0.0, hub.stars.value_at(event.at) + float(p["delta"]))
    return replace(hub, stars=hub.stars.with_point(event.at, value))


EVENT_TYPES = event_types(
    (
        "preload_repo",
        EventType(
            schema=PreloadRepo,
            reduce=reduce_preload_repo,
            help="The repository at the start; baselines are measured after it.",
            catalog_refs={key: table for key, (table, _) in LOADED.items()},
            preload=True,
        ),
    ),
    arrival("new_issue", "issue_id", "issues", deliver_issues, help="An issue is filed."),
    (
        "stars_waypoint",
        EventType(
            StarsWaypoint, reduce_stars_waypoint, "The star count steps to a value (or by delta)."
        ),
    ),
    arrival(
        "new_pull_request",
        "pr_id",
        "prs",
        deliver_prs,
        help="A pull request is opened.",
        description="catalog pull request id",
    ),
    arrival("new_commit", "commit_id", "commits", push_commits, help="A commit is pushed."),
    arrival(
        "new_workflow_run",
        "run_id",
        "workflow-runs",
        newest_first(deliver_runs),
        help="A workflow run starts.",
        description="catalog workflow run id",
    ),
)


# --- baselines and evaluation tables (the original's names, so its eval_sql runs unchanged) ------

BASELINES = MappingProxyType(
    {
        "star_count": star_count,  # moves with the clock: read at the preload's moment
        **counted(
            {
                "fork_count": lambda hub: hub.forks,
                "watch_count": lambda hub: hub.watchers,
                "issue_count": lambda hub: len(hub.issues),
                "pr_count": lambda hub: len(hub.prs),
                "commit_count": lambda hub: len(hub.commits),
                "comment_count": self_comment_count,
            }
        ),
    }
)


def _text(value: Any) -> str:
    """The original's encoding of a repository value: JSON for dicts and lists, else str()."""
    return json.dumps(value) if isinstance(value, dict | list) else str(value)


def _entries(mapping: Mapping[str, Any]) -> Iterable[Keyed]:
    return (Keyed(key, value) for key, value in mapping.items())


def repo_flags(hub: Hub, now: float) -> dict[str, str]:
    """The user's flags on the repository and its counters; `star_count` is the live one."""
    return {
        "starred": "1" if hub.starred else "0",
        "watched": "1" if hub.watched else "0",
        "forked": "1" if hub.forked else "0",
        "star_count": str(star_count(hub, now)),
        "fork_count": str(hub.forks),
        "watch_count": str(hub.watchers),
    }


def json_rows(name: str, rows: Callable[[Hub], Mapping[str, Mapping[str, Any]]]) -> Table[Hub]:
    """A table the original exported as (id, the catalog row as JSON)."""
    return Table(
        name,
        lambda hub, now: _entries(rows(hub)),
        {"id TEXT": KEY, "data TEXT": lambda row: json.dumps(dict(row.value))},
    )


def catalog_runs(hub: Hub) -> Mapping[str, Mapping[str, Any]]:
    runs = records.table(hub.catalog, "workflow-runs")
    return {run_id: runs[run_id] for run_id in hub.runs}


def passed_through(table: str) -> Callable[[Hub], Mapping[str, Mapping[str, Any]]]:
    return lambda hub: hub.records.get(table, EMPTY)


materialize = tables(
    Table.keyed(
        "repository", "repo", {"key TEXT": KEY, "value TEXT": lambda row: _text(row.value)}
    ),
    Table(
        "files",
        lambda hub, now: hub.files.values(),
        {**named("id TEXT", "name TEXT", "path TEXT", "type TEXT"), "parentId TEXT": "parent_id"},
    ),
    Table(
        "issues",
        lambda hub, now: hub.issues.values(),
        named("id TEXT", "number INTEGER", "title TEXT", "body TEXT", "state TEXT", "author TEXT"),
    ),
    # `isViewed`: the original kept it in the session without exporting it, yet its scenarios'
    # eval_sql read it; exported here as 0/1. The user's own issues are not in this table.
    Table(
        "issue_states",
        lambda hub, now: (row for row in _entries(hub.issue_states) if row.key in hub.issues),
        {"issue_id TEXT": KEY, "state TEXT": "value.state", "isViewed INTEGER": "value.viewed"},
    ),
    Table(
        "prs",
        lambda hub, now: hub.prs.values(),
        named("id TEXT", "number INTEGER", "title TEXT", "state TEXT", "author TEXT"),
    ),
    Table(
        "pr_states",
        lambda hub, now: (Keyed(pr_id, hub.pr_state(pr_id)) for pr_id in hub.prs),
        {"pr_id TEXT": KEY, "state TEXT": "value"},
    ),
    Table(
        "commits",
        lambda hub, now: hub.commits.values(),
        named("id TEXT", "sha TEXT", "message TEXT", "author TEXT"),
    ),
    Table(
        "user_created_comments",
        lambda hub, now: hub.user_comments,
        named("id TEXT", "target_type TEXT", "target_id TEXT", "body TEXT"),
    ),
    Table(
        "user_created_issues",
        lambda hub, now: hub.user_issues.values(),
        named("id TEXT", "title TEXT", "body TEXT"),
    ),
    # The original had no way to create a pull request either: always empty.
    Table("user_created_prs", lambda hub, now: (), named("id TEXT", "title TEXT", "body TEXT")),
    Table("merged_prs", lambda hub, now: hub.merged, {"pr_id TEXT": str}),
    Table("following_users", lambda hub, now: hub.following, {"username TEXT": str}),
    Table(
        "repo_flags",
        lambda hub, now: _entries(repo_flags(hub, now)),
        {"key TEXT": KEY, "value TEXT": "value"},
    ),
    json_rows("runs", catalog_runs),
    *(json_rows(table.replace("-", "_"), passed_through(table)) for table in records.PASS_THROUGH),
)


MICROHUB = Environment(
    name=ENVIRONMENT,
    title="MicroHub",
    initial_state=empty_hub,
    event_types=EVENT_TYPES,
    actions=ACTIONS,
    baselines=BASELINES,
    materialize=materialize,
    urlconf="apps.microhub.urls",
    implicit_actions=(
        # Opening an issue marks it viewed, as the original's issue page did on opening.
        ImplicitAction(
            page="issue",
            param="issue_id",
            action="view_issue",
            payload=lambda issue_id: {"issue_id": issue_id},
            applies=lambda hub, issue_id: (
                issue_id in hub.issues and not hub.issue_states[issue_id].viewed
            ),
        ),
    ),
    sample_pages=sample_pages,
)
