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
import sqlite3
from collections.abc import Mapping
from dataclasses import replace
from types import MappingProxyType
from typing import Annotated, Any

from pydantic import Field, model_validator

from apps.kit.legacy_tables import Table
from apps.kit.waypoints import Waypoints
from apps.microhub import catalog as records
from apps.microhub.actions import ACTIONS
from apps.microhub.bench import sample_pages
from apps.microhub.state import (
    ENVIRONMENT,
    Hub,
    IssueState,
    frozen,
    next_issue_number,
    self_comment_count,
    star_count,
)
from events.registry import Environment, EventType, ImplicitAction, LoggedEvent, Measure, timeless
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


# --- preload_repo -----------------------------------------------------------------------------


class PreloadRepo(Payload):
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


PASS_THROUGH_IDS = {
    "workflows": "workflow_ids",
    "wiki": "wiki_ids",
    "projects": "project_ids",
    "activity": "activity_ids",
    "releases": "release_ids",
    "labels": "label_ids",
    "security": "security_ids",
    "code-scanning": "scanning_ids",
    "deployments": "deployment_ids",
    "packages": "package_ids",
}


def _ids(hub: Hub, payload: Mapping[str, Any], table: str, key: str) -> list[str]:
    ids = payload.get(key, WILDCARD)
    return list(dict.fromkeys(hub.catalog.expand(ENVIRONMENT, table, ids)))


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
    """The repository as the task starts; the core measures the baselines right after."""
    p, catalog = event.payload, hub.catalog
    start = event.at - float(p.get("preload_age_offset_ms") or 0) / 1000.0
    repo = _preloaded_repo(hub, p)

    def aged(table: str, row_id: str) -> float:
        return start - records.age_of(records.table(catalog, table)[row_id])

    issues = {}
    for i in _ids(hub, p, "issues", "issue_ids"):
        if i in records.table(catalog, "issues"):
            issues[i] = records.catalog_issue(catalog, i, opened_at=aged("issues", i))
    prs = {}
    for i in _ids(hub, p, "prs", "pr_ids"):
        if i in records.table(catalog, "prs"):
            prs[i] = records.catalog_pr(catalog, i, opened_at=aged("prs", i))
    commits = {}
    for i in _ids(hub, p, "commits", "commit_ids"):
        if i in records.table(catalog, "commits"):
            commits[i] = records.catalog_commit(catalog, i, at=aged("commits", i))
    runs = {}
    for i in _ids(hub, p, "workflow-runs", "run_ids"):
        if i in records.table(catalog, "workflow-runs"):
            runs[i] = records.catalog_run(catalog, i, at=aged("workflow-runs", i))
    files = {
        i: records.catalog_file(catalog, i)
        for i in _ids(hub, p, "files", "file_ids")
        if i in records.table(catalog, "files")
    }
    passed = {
        table: frozen(
            {
                i: records.table(catalog, table)[i]
                for i in _ids(hub, p, table, key)
                if i in records.table(catalog, table)
            }
        )
        for table, key in PASS_THROUGH_IDS.items()
    }
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
        issues=frozen(issues),
        issue_states=frozen(
            {
                **{i: IssueState(state=issue.state) for i, issue in issues.items()},
                **{i: s for i, s in hub.issue_states.items() if i in hub.user_issues},
            }
        ),
        prs=frozen(prs),
        pr_states=frozen({i: ("merged" if i in hub.merged else pr.state) for i, pr in prs.items()}),
        commits=frozen(commits),
        runs=frozen(runs),
        files=frozen(files),
        records=frozen(passed),
    )


# --- arrivals -----------------------------------------------------------------------------------


class NewIssue(Payload):
    issue_id: str = Field(description="catalog issue id")


class NewPullRequest(Payload):
    pr_id: str = Field(description="catalog pull request id")


class NewCommit(Payload):
    commit_id: str = Field(description="catalog commit id")


class NewWorkflowRun(Payload):
    run_id: str = Field(description="catalog workflow run id")


def reduce_new_issue(hub: Hub, event: LoggedEvent) -> Hub:
    """Filed now; renumbered after every issue so far so it sorts to the top (the original's
    rule). An issue already there, or missing from the catalog, changes nothing."""
    issue_id = event.payload["issue_id"]
    if issue_id in hub.issues:
        return hub
    issue = records.catalog_issue(
        hub.catalog, issue_id, opened_at=event.at, number=next_issue_number(hub)
    )
    if issue is None:
        return hub
    issue = replace(issue, comments=())  # filed just now: nobody has answered yet
    return replace(
        hub,
        issues=frozen({**hub.issues, issue_id: issue}),
        issue_states=frozen({**hub.issue_states, issue_id: IssueState(state=issue.state)}),
    )


def reduce_new_pull_request(hub: Hub, event: LoggedEvent) -> Hub:
    """Opened now, numbered after every issue and pull request so far (they share numbers)."""
    pr_id = event.payload["pr_id"]
    if pr_id in hub.prs:
        return hub
    numbers = [i.number for i in (*hub.issues.values(), *hub.user_issues.values())]
    numbers += [pr.number for pr in hub.prs.values()]
    pr = records.catalog_pr(
        hub.catalog, pr_id, opened_at=event.at, number=max(numbers, default=0) + 1
    )
    if pr is None:
        return hub
    pr = replace(pr, comments=())
    return replace(
        hub,
        prs=frozen({**hub.prs, pr_id: pr}),
        pr_states=frozen({**hub.pr_states, pr_id: pr.state}),
    )


def reduce_new_commit(hub: Hub, event: LoggedEvent) -> Hub:
    """Pushed now: first in the history, and one more in the commit count."""
    commit_id = event.payload["commit_id"]
    commit = (
        None
        if commit_id in hub.commits
        else records.catalog_commit(hub.catalog, commit_id, at=event.at)
    )
    if commit is None:
        return hub
    return replace(
        hub,
        commits=frozen({commit_id: commit, **hub.commits}),
        commit_total=hub.commit_total + 1,
    )


def reduce_new_workflow_run(hub: Hub, event: LoggedEvent) -> Hub:
    run_id = event.payload["run_id"]
    run = None if run_id in hub.runs else records.catalog_run(hub.catalog, run_id, at=event.at)
    if run is None:
        return hub
    return replace(hub, runs=frozen({run_id: run, **hub.runs}))


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


EVENT_TYPES: Mapping[str, EventType] = MappingProxyType(
    {
        "preload_repo": EventType(
            schema=PreloadRepo,
            reduce=reduce_preload_repo,
            help="The repository at the start; baselines are measured after it.",
            catalog_refs={
                "issue_ids": "issues",
                "pr_ids": "prs",
                "commit_ids": "commits",
                "run_ids": "workflow-runs",
                "file_ids": "files",
            },
            preload=True,
        ),
        "new_issue": EventType(
            NewIssue, reduce_new_issue, "An issue is filed.", {"issue_id": "issues"}
        ),
        "stars_waypoint": EventType(
            StarsWaypoint, reduce_stars_waypoint, "The star count steps to a value (or by delta)."
        ),
        "new_pull_request": EventType(
            NewPullRequest, reduce_new_pull_request, "A pull request is opened.", {"pr_id": "prs"}
        ),
        "new_commit": EventType(
            NewCommit, reduce_new_commit, "A commit is pushed.", {"commit_id": "commits"}
        ),
        "new_workflow_run": EventType(
            NewWorkflowRun,
            reduce_new_workflow_run,
            "A workflow run starts.",
            {"run_id": "workflow-runs"},
        ),
    }
)


# --- baselines and evaluation tables (the original's names, so its eval_sql runs unchanged) ------

BASELINES: Mapping[str, Measure] = MappingProxyType(
    {
        "star_count": star_count,
        "fork_count": timeless(lambda hub: hub.forks),
        "watch_count": timeless(lambda hub: hub.watchers),
        "issue_count": timeless(lambda hub: len(hub.issues)),
        "pr_count": timeless(lambda hub: len(hub.prs)),
        "commit_count": timeless(lambda hub: len(hub.commits)),
        "comment_count": timeless(self_comment_count),
    }
)

REPOSITORY = Table("repository", ("key TEXT", "value TEXT"))
FILES = Table("files", ("id TEXT", "name TEXT", "path TEXT", "type TEXT", "parentId TEXT"))
ISSUES = Table(
    "issues",
    ("id TEXT", "number INTEGER", "title TEXT", "body TEXT", "state TEXT", "author TEXT"),
)
ISSUE_STATES = Table("issue_states", ("issue_id TEXT", "state TEXT", "isViewed INTEGER"))
PRS = Table("prs", ("id TEXT", "number INTEGER", "title TEXT", "state TEXT", "author TEXT"))
PR_STATES = Table("pr_states", ("pr_id TEXT", "state TEXT"))
COMMITS = Table("commits", ("id TEXT", "sha TEXT", "message TEXT", "author TEXT"))
USER_COMMENTS = Table(
    "user_created_comments", ("id TEXT", "target_type TEXT", "target_id TEXT", "body TEXT")
)
USER_ISSUES = Table("user_created_issues", ("id TEXT", "title TEXT", "body TEXT"))
USER_PRS = Table("user_created_prs", ("id TEXT", "title TEXT", "body TEXT"))
MERGED_PRS = Table("merged_prs", ("pr_id TEXT",))
FOLLOWING = Table("following_users", ("username TEXT",))
REPO_FLAGS = Table("repo_flags", ("key TEXT", "value TEXT"))
DATA_TABLES = {
    name: Table(name, ("id TEXT", "data TEXT")) for name in ("runs", *records.PASS_THROUGH.values())
}


def _text(value: Any) -> str:
    """The original's encoding of a repository value: JSON for dicts and lists, else str()."""
    return json.dumps(value) if isinstance(value, dict | list) else str(value)


def materialize(hub: Hub, now: float, conn: sqlite3.Connection) -> None:
    """The original's tables as of `now`; `repo_flags.star_count` is the live count at `now`.

    `issue_states` carries `isViewed` (the original kept it in the session but did not export
    it; its scenarios' eval_sql read it, so it is exported here as 0/1)."""
    REPOSITORY.write(conn, ((k, _text(v)) for k, v in hub.repo.items()))
    FILES.write(conn, ((f.id, f.name, f.path, f.type, f.parent_id) for f in hub.files.values()))
    ISSUES.write(
        conn,
        ((i.id, i.number, i.title, i.body, i.state, i.author) for i in hub.issues.values()),
    )
    ISSUE_STATES.write(
        conn,
        (
            (issue_id, s.state, s.viewed)
            for issue_id, s in hub.issue_states.items()
            if issue_id in hub.issues
        ),
    )
    PRS.write(conn, ((p.id, p.number, p.title, p.state, p.author) for p in hub.prs.values()))
    PR_STATES.write(conn, ((pr_id, hub.pr_state(pr_id)) for pr_id in hub.prs))
    COMMITS.write(conn, ((c.id, c.sha, c.message, c.author) for c in hub.commits.values()))
    USER_COMMENTS.write(
        conn, ((c.id, c.target_type, c.target_id, c.body) for c in hub.user_comments)
    )
    USER_ISSUES.write(conn, ((i.id, i.title, i.body) for i in hub.user_issues.values()))
    USER_PRS.write(conn, ())  # the original had no way to create one either
    MERGED_PRS.write(conn, ((pr_id,) for pr_id in hub.merged))
    FOLLOWING.write(conn, ((u,) for u in hub.following))
    REPO_FLAGS.write(
        conn,
        (
            ("starred", "1" if hub.starred else "0"),
            ("watched", "1" if hub.watched else "0"),
            ("forked", "1" if hub.forked else "0"),
            ("star_count", str(star_count(hub, now))),
            ("fork_count", str(hub.forks)),
            ("watch_count", str(hub.watchers)),
        ),
    )
    catalog_runs = records.table(hub.catalog, "workflow-runs")
    DATA_TABLES["runs"].write(
        conn, ((run_id, json.dumps(dict(catalog_runs[run_id]))) for run_id in hub.runs)
    )
    for table, name in records.PASS_THROUGH.items():
        rows = hub.records.get(table, {})
        DATA_TABLES[name].write(conn, ((i, json.dumps(dict(r))) for i, r in rows.items()))


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
