"""Catalog records (SentinelBench format, the original's camelCase shapes) → MicroHub values.

Tables in `microhub/`: repository, issues, prs, commits, files, workflow-runs, workflows,
labels, and the tables the original only passed through (wiki, projects, releases…). People are
named by username; their display names come from the shared `users.json`.

Ages: a catalog row has no date. As the original did, a preloaded row is `order × 30 min` old
(one step more, so the newest does not read "just now"), plus the preload's age offset; a row
arriving during the task is dated then, and an issue or pull request has no answers yet.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from apps.kit.arrivals import Stamp
from apps.microhub.state import (
    ENVIRONMENT,
    Check,
    Comment,
    Commit,
    Issue,
    Job,
    Label,
    Person,
    PullRequest,
    RepoFile,
    Step,
    WorkflowRun,
)

STEP_S = 30 * 60.0  # the original's age step between catalog rows
COMMENT_GAP_S = 20 * 60.0

# Tables the original only passed through: catalog table → the preload's id list. Each is
# exported as an (id, JSON) table of the same name (`code-scanning` → `code_scanning`).
PASS_THROUGH = {
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


def table(catalog: Any, name: str) -> Mapping[str, Mapping[str, Any]]:
    return catalog.table(ENVIRONMENT, name)


def people(catalog: Any) -> Mapping[str, str]:
    """username → display name, for every user of the shared users file."""
    return {
        str(u["username"]): str(u.get("name") or u["username"])
        for u in catalog.users.values()
        if u.get("username")
    }


def display_name(catalog: Any, username: str) -> str:
    return catalog.index(people).get(username, username)


def persons(catalog: Any, usernames: Any) -> tuple[Person, ...]:
    return tuple(Person(str(u), display_name(catalog, str(u))) for u in usernames or ())


def repository_record(catalog: Any) -> Mapping[str, Any]:
    """The first repository of the catalog (the original shows only that one)."""
    return next(iter(table(catalog, "repository").values()), {})


def labels(catalog: Any) -> Mapping[str, Label]:
    return {
        label_id: Label(
            id=label_id,
            name=str(r.get("name", label_id)),
            color=str(r.get("color") or "#ededed"),
            description=str(r.get("description") or ""),
        )
        for label_id, r in table(catalog, "labels").items()
    }


def dated(record: Mapping[str, Any], stamp: Stamp) -> float:
    """When a row arrived: a preloaded one its age before the start (`stamp.at`), one arriving
    during the task at that moment."""
    return stamp.at - (int(record.get("order") or 0) + 1) * STEP_S if stamp.preloaded else stamp.at


def _labels(catalog: Any, record: Mapping[str, Any]) -> tuple[Label, ...]:
    known = catalog.index(labels)
    return tuple(known[i] for i in record.get("labelIds") or () if i in known)


def _comments(catalog: Any, record: Mapping[str, Any], stamp: Stamp) -> tuple[Comment, ...]:
    """The catalog thread of a preloaded issue or pull request; one arriving now has none yet."""
    if not stamp.preloaded:
        return ()
    opened_at = dated(record, stamp)
    return tuple(
        Comment(
            id=str(c.get("id", f"{record['id']}-c{k}")),
            author=str(c.get("author", "")),
            author_name=display_name(catalog, str(c.get("author", ""))),
            body=str(c.get("body", "")),
            at=opened_at + (k + 1) * COMMENT_GAP_S,
            reactions=tuple(
                (str(r.get("emoji", "")), int(r.get("count") or 0))
                for r in c.get("reactions") or ()
            ),
        )
        for k, c in enumerate(record.get("comments") or ())
    )


def _post(catalog: Any, record: Mapping[str, Any], stamp: Stamp, number: int | None):
    """What an issue and a pull request read alike; `number` None keeps the catalog's."""
    author = str(record.get("author", ""))
    return {
        "number": int(record.get("number") or 0) if number is None else number,
        "title": str(record.get("title", "")),
        "body": str(record.get("body") or ""),
        "state": str(record.get("state") or "open"),
        "author": author,
        "author_name": display_name(catalog, author),
        "opened_at": dated(record, stamp),
        "labels": _labels(catalog, record),
        "comments": _comments(catalog, record, stamp),
    }


def catalog_issue(catalog: Any, issue_id: str, stamp: Stamp, number: int | None = None):
    record = table(catalog, "issues").get(issue_id)
    if record is None:
        return None
    assignees = persons(catalog, record.get("assignees"))
    return Issue(id=issue_id, **_post(catalog, record, stamp, number), assignees=assignees)


def catalog_pr(catalog: Any, pr_id: str, stamp: Stamp, number: int | None = None):
    record = table(catalog, "prs").get(pr_id)
    if record is None:
        return None
    return PullRequest(
        id=pr_id,
        **_post(catalog, record, stamp, number),
        source=str(record.get("sourceBranch", "")),
        target=str(record.get("targetBranch", "main")),
        review_status=str(record.get("reviewStatus") or "review-required"),
        reviewers=persons(catalog, record.get("reviewers")),
        checks=tuple(
            Check(str(c.get("name", "")), str(c.get("status", "")))
            for c in record.get("checks") or ()
        ),
        commits=int(record.get("commits") or 0),
        additions=int(record.get("additions") or 0),
        deletions=int(record.get("deletions") or 0),
        files_changed=int(record.get("filesChanged") or 0),
    )


def catalog_commit(catalog: Any, commit_id: str, stamp: Stamp) -> Commit | None:
    record = table(catalog, "commits").get(commit_id)
    if record is None:
        return None
    author = str(record.get("author", ""))
    files = record.get("filesChanged")
    return Commit(
        id=commit_id,
        sha=str(record.get("sha", "")),
        message=str(record.get("message", "")),
        author=author,
        author_name=display_name(catalog, author),
        at=dated(record, stamp),
        additions=int(record.get("additions") or 0),
        deletions=int(record.get("deletions") or 0),
        files=tuple(str(f) for f in files) if isinstance(files, list) else (),
        verified=bool(record.get("verified")),
    )


def catalog_file(catalog: Any, file_id: str) -> RepoFile | None:
    record = table(catalog, "files").get(file_id)
    if record is None:
        return None
    last = record.get("lastCommit") or {}
    content = str(record.get("content") or "")
    return RepoFile(
        id=file_id,
        name=str(record.get("name", "")),
        path=str(record.get("path", "")),
        type=str(record.get("type") or "file"),
        parent_id=record.get("parentId"),
        content=content,
        size=int(record.get("size") or len(content.encode())),
        language=str(record.get("language") or ""),
        last_commit_sha=str(last.get("sha", "")),
        last_commit_message=str(last.get("message", "")),
    )


def catalog_run(catalog: Any, run_id: str, stamp: Stamp) -> WorkflowRun | None:
    record = table(catalog, "workflow-runs").get(run_id)
    if record is None:
        return None
    actor = str(record.get("actor", ""))
    commit = record.get("commit") or {}
    return WorkflowRun(
        id=run_id,
        workflow_id=str(record.get("workflowId", "")),
        workflow_name=str(record.get("workflowName", "")),
        number=int(record.get("runNumber") or 0),
        status=str(record.get("status") or "completed"),
        conclusion=str(record.get("conclusion") or ""),
        branch=str(record.get("branch", "")),
        commit_sha=str(commit.get("sha", "")),
        commit_message=str(commit.get("message", "")),
        actor=actor,
        actor_name=display_name(catalog, actor),
        event=str(record.get("event", "")),
        duration=int(record.get("duration") or 0),
        at=dated(record, stamp),
        jobs=tuple(
            Job(
                name=str(j.get("name", "")),
                status=str(j.get("status", "")),
                conclusion=str(j.get("conclusion") or ""),
                duration=int(j.get("duration") or 0),
                steps=tuple(
                    Step(
                        str(s.get("name", "")),
                        str(s.get("conclusion") or s.get("status") or ""),
                        int(s.get("duration") or 0),
                    )
                    for s in j.get("steps") or ()
                ),
            )
            for j in record.get("jobs") or ()
        ),
    )
