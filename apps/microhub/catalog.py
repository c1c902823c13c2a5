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
from apps.kit.records import Given, read, reader
from apps.microhub.state import (
    ENVIRONMENT,
    Comment,
    Commit,
    Issue,
    Label,
    Person,
    PullRequest,
    RepoFile,
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


def repository_record(catalog: Any) -> Mapping[str, Any]:
    """The first repository of the catalog (the original shows only that one)."""
    return next(iter(table(catalog, "repository").values()), {})


def labels(catalog: Any) -> Mapping[str, Label]:
    return {
        label_id: read(Label, r, id=label_id, name=str(r.get("name", label_id)))
        for label_id, r in table(catalog, "labels").items()
    }


# --- what a record reads with the catalog or the arrival's stamp (`Given`) -------------------


def arrived(catalog: Any, record: Mapping[str, Any], stamp: Stamp) -> float:
    """When a row arrived: a preloaded one its age before the start (`stamp.at`), one arriving
    during the task at that moment."""
    return stamp.at - (int(record.get("order") or 0) + 1) * STEP_S if stamp.preloaded else stamp.at


def name_of(key: str) -> Given:
    """The display name of the person whose username is at `key`."""
    return lambda catalog, record, stamp: display_name(catalog, str(record.get(key, "")))


def people_at(key: str) -> Given:
    return lambda catalog, record, stamp: tuple(
        Person(str(u), display_name(catalog, str(u))) for u in record.get(key) or ()
    )


def labels_of(catalog: Any, record: Mapping[str, Any], stamp: Stamp) -> tuple[Label, ...]:
    known = catalog.index(labels)
    return tuple(known[i] for i in record.get("labelIds") or () if i in known)


def thread(catalog: Any, record: Mapping[str, Any], stamp: Stamp) -> tuple[Comment, ...]:
    """The catalog thread of a preloaded issue or pull request; one arriving now has none yet."""
    if not stamp.preloaded:
        return ()
    opened_at = arrived(catalog, record, stamp)
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


# --- each record type, its catalog fields declared in state.py ------------------------------

# What an issue and a pull request read with the catalog or the stamp.
POSTED: dict[str, Given] = {
    "author_name": name_of("author"),
    "opened_at": arrived,
    "labels": labels_of,
    "comments": thread,
}

issue = reader(ENVIRONMENT, "issues", Issue, **POSTED, assignees=people_at("assignees"))
pull_request = reader(ENVIRONMENT, "prs", PullRequest, **POSTED, reviewers=people_at("reviewers"))
commit = reader(ENVIRONMENT, "commits", Commit, author_name=name_of("author"), at=arrived)
repo_file = reader(ENVIRONMENT, "files", RepoFile)
workflow_run = reader(
    ENVIRONMENT, "workflow-runs", WorkflowRun, actor_name=name_of("actor"), at=arrived
)
