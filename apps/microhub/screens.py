"""What each MicroHub screen shows: pure functions of the state, memoised per state.

Times are not decided here (they move with the clock): rows carry their moment (`at`) and the
templates render it with the simtime filters, which register when the text next changes.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass

from apps.kit.derived import per_state
from apps.microhub.state import (
    Comment,
    Commit,
    Hub,
    Issue,
    Post,
    PullRequest,
    RepoFile,
    WorkflowRun,
)


@dataclass(frozen=True)
class Counts:
    open_issues: int
    closed_issues: int
    open_prs: int
    closed_prs: int
    runs: int


@dataclass(frozen=True)
class PostRow:
    """An issue or a pull request in its list: its current state, how many comments it has."""

    post: Post
    state: str
    comments: int


@per_state()
def counts(hub: Hub) -> Counts:
    open_issues = sum(1 for i in hub.issue_states.values() if i.state == "open")
    open_prs = sum(1 for pr_id in hub.prs if hub.pr_state(pr_id) == "open")
    return Counts(
        open_issues=open_issues,
        closed_issues=len(hub.issue_states) - open_issues,
        open_prs=open_prs,
        closed_prs=len(hub.prs) - open_prs,
        runs=len(hub.runs),
    )


@per_state()
def comments_on(hub: Hub, target_type: str, target_id: str) -> tuple[Comment, ...]:
    """The thread of an issue or pull request: its catalog comments, then the user's."""
    item = hub.issue(target_id) if target_type == "issue" else hub.prs.get(target_id)
    own = tuple(
        c for c in hub.user_comments if c.target_type == target_type and c.target_id == target_id
    )
    return (item.comments if item else ()) + own


def _issues(hub: Hub) -> list[Issue]:
    return [*hub.issues.values(), *hub.user_issues.values()]


@per_state()
def issue_rows(hub: Hub, state: str, q: str, sort: str) -> tuple[PostRow, ...]:
    """The Issues tab: open or closed, searched in title and body (case-insensitive)."""
    needle = q.lower()
    rows = [
        PostRow(i, hub.issue_state(i.id), len(comments_on(hub, "issue", i.id)))
        for i in _issues(hub)
        if hub.issue_state(i.id) == state
        and (not needle or needle in i.title.lower() or needle in i.body.lower())
    ]
    if sort == "comments":
        rows.sort(key=lambda r: (-r.comments, -r.post.number))
    else:
        rows.sort(key=lambda r: r.post.number, reverse=sort == "newest")
    return tuple(rows)


@per_state()
def search_counts(hub: Hub, q: str) -> tuple[int, int]:
    """(open, closed) issues matching the search, for the toggle above the list."""
    return len(issue_rows(hub, "open", q, "newest")), len(issue_rows(hub, "closed", q, "newest"))


@per_state()
def pr_rows(hub: Hub, state: str) -> tuple[PostRow, ...]:
    """Pull requests, newest number first; merged ones count as closed."""
    wanted = (lambda s: s == "open") if state == "open" else (lambda s: s != "open")
    rows = [
        PostRow(pr, hub.pr_state(pr.id), len(comments_on(hub, "pr", pr.id)))
        for pr in hub.prs.values()
        if wanted(hub.pr_state(pr.id))
    ]
    rows.sort(key=lambda r: r.post.number, reverse=True)
    return tuple(rows)


@per_state()
def folder_entries(hub: Hub, parent_path: str) -> tuple[RepoFile, ...]:
    """A folder's entries as GitHub lists them: folders first, then files, by name."""
    parent_id = None
    if parent_path:
        folder = file_at(hub, parent_path)
        parent_id = folder.id if folder else "-"
    entries = [f for f in hub.files.values() if f.parent_id == parent_id]
    return tuple(sorted(entries, key=lambda f: (not f.is_folder, f.name.lower())))


@per_state()
def file_at(hub: Hub, path: str) -> RepoFile | None:
    return next((f for f in hub.files.values() if f.path == path), None)


def readme(hub: Hub, folder: str = "") -> RepoFile | None:
    return next(
        (f for f in folder_entries(hub, folder) if f.name.lower().startswith("readme")), None
    )


@per_state()
def commit_history(hub: Hub) -> tuple[Commit, ...]:
    return tuple(sorted(hub.commits.values(), key=lambda c: c.at, reverse=True))


def latest_commit(hub: Hub) -> Commit | None:
    return next(iter(commit_history(hub)), None)


@per_state()
def workflow_runs(hub: Hub, workflow: str = "") -> tuple[WorkflowRun, ...]:
    runs = [r for r in hub.runs.values() if not workflow or r.workflow_id == workflow]
    return tuple(sorted(runs, key=lambda r: r.at, reverse=True))


@per_state()
def workflows(hub: Hub) -> tuple[tuple[str, str], ...]:
    """(id, name) of each workflow, from the catalog's list or else the runs."""
    named = {i: str(r.get("name", i)) for i, r in hub.records.get("workflows", {}).items()}
    for run in hub.runs.values():
        named.setdefault(run.workflow_id, run.workflow_name)
    return tuple(named.items())


@per_state()
def contributors(hub: Hub) -> tuple[tuple[str, str], ...]:
    """(username, name) of everyone with a commit here, most commits first."""
    tally = Counter((c.author, c.author_name) for c in hub.commits.values())
    return tuple(person for person, _ in tally.most_common())


def person_activity(hub: Hub, username: str) -> tuple[Issue | PullRequest | Commit, ...]:
    """What a person did here lately (their issues, pull requests and commits)."""
    items = [i for i in _issues(hub) if i.author == username]
    items += [p for p in hub.prs.values() if p.author == username]
    return tuple(items[:5])


@dataclass(frozen=True)
class Organization:
    login: str
    name: str
    description: str


def organization(hub: Hub) -> Organization:
    """The repository's owner as an organization page (the original made one up when the owner
    was no known user): the company entity whose name matches, else the owner's login."""
    login = hub.owner
    entity = next(
        (
            e
            for e in hub.catalog.entities.values()
            if e.get("type") == "company" and login.lower() in str(e.get("name", "")).lower()
        ),
        {},
    )
    return Organization(
        login, str(entity.get("name") or login), str(entity.get("description") or "")
    )
