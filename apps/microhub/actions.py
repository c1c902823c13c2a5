"""What the user can do to the repository: `Action(schema, decide, reduce, page=…)` per name.

`decide(hub, payload)` checks the request against the current state and returns the payload to
log (with the id it chose for something new); `reduce` applies a logged action and never raises.

Fixed from the original (§6 of the reference): a comment's author is the user, not a
hard-coded person; star, watch and issue state are set explicitly (star / unstar, close /
reopen), not toggled, so a repeated request cannot flip them back; only an open pull request
can be merged; the repository settings never leak into the catalog.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import replace
from types import MappingProxyType
from typing import Any, Literal

from pydantic import Field

from apps.kit.deciding import found, required_text
from apps.kit.fields import ItemId, Line, Text
from apps.kit.state import with_items
from apps.microhub.state import (
    MERGE_STRATEGIES,
    VISIBILITIES,
    Comment,
    Hub,
    Issue,
    UserRepo,
    next_issue_number,
    with_issue_state,
)
from events.registry import Action, ActionRejected, LoggedEvent, PageStep
from events.schemas import Payload

REPO_NAME = re.compile(r"[A-Za-z0-9._-]{1,100}")


class IssueId(Payload):
    issue_id: ItemId = Field(description="id of an issue in the repository (e.g. i14)")


class PrId(Payload):
    pr_id: ItemId = Field(description="id of a pull request (e.g. pr3)")


class NewIssue(Payload):
    title: Line
    body: Text = ""


class IssueComment(IssueId):
    body: Text


class PrComment(PrId):
    body: Text


class Merge(PrId):
    strategy: Literal[MERGE_STRATEGIES] = "merge"


class NoFields(Payload):
    pass


class NewRepository(Payload):
    name: Line
    description: Text = ""
    visibility: Literal[VISIBILITIES] = "public"
    add_readme: bool = False
    add_gitignore: bool = False


class RepositorySettings(Payload):
    name: Line | None = None
    description: Text | None = None
    visibility: Literal[VISIBILITIES] | None = None


class Username(Payload):
    username: ItemId


# --- checks ----------------------------------------------------------------------------------------


def existing_issue(hub: Hub, issue_id: str) -> Issue:
    issue = hub.issue(issue_id)
    if issue is None:  # unknown and not-yet-filed look the same
        raise ActionRejected(f"no issue {issue_id!r} in {hub.owner}/{hub.name}", status=404)
    return issue


def existing_pr(hub: Hub, pr_id: str):
    return found(hub.prs, pr_id, "pull request", f"in {hub.owner}/{hub.name}")


# --- issues -----------------------------------------------------------------------------------------


def decide_create_issue(hub: Hub, payload: dict) -> dict:
    title = required_text(payload, "title")
    return {
        "id": f"user-issue-{len(hub.user_issues) + 1}",
        "title": title,
        "body": payload.get("body", ""),
    }


def reduce_create_issue(hub: Hub, event: LoggedEvent) -> Hub:
    p = event.payload
    issue = Issue(
        id=p["id"],
        number=next_issue_number(hub),
        title=p["title"],
        body=p["body"],
        state="open",
        author=hub.self_username,
        author_name=hub.self_name,
        opened_at=event.at,
    )
    hub = with_items(hub, "user_issues", [(issue.id, issue)])
    return with_issue_state(hub, issue.id, state="open")


def decide_view_issue(hub: Hub, payload: dict) -> dict:
    if payload["issue_id"] not in hub.issues:  # the original recorded views of filed issues only
        existing_issue(hub, payload["issue_id"])
        raise ActionRejected(f"issue {payload['issue_id']!r} was created here, not filed", 404)
    return payload


def set_issue(**changes) -> Callable[[Hub, LoggedEvent], Hub]:
    def reduce(hub: Hub, event: LoggedEvent) -> Hub:
        if hub.issue(event.payload["issue_id"]) is None:
            return hub
        return with_issue_state(hub, event.payload["issue_id"], **changes)

    return reduce


def decide_set_state(wanted: str) -> Callable[[Hub, dict], dict]:
    def decide(hub: Hub, payload: dict) -> dict:
        existing_issue(hub, payload["issue_id"])
        if hub.issue_state(payload["issue_id"]) == wanted:
            raise ActionRejected(f"issue {payload['issue_id']!r} is already {wanted}", 409)
        return payload

    return decide


# --- comments ---------------------------------------------------------------------------------------


def comment_action(target_type: str, payload: type[Payload], **where: Any) -> Action[Hub]:
    """Commenting as the user on the issue or pull request `payload[<target_type>_id]`."""
    key = f"{target_type}_id"
    existing = existing_issue if target_type == "issue" else existing_pr

    def decide(hub: Hub, payload: dict) -> dict:
        existing(hub, payload[key])
        body = required_text(payload, "body")
        return {key: payload[key], "body": body, "id": f"user-comment-{len(hub.user_comments) + 1}"}

    def reduce(hub: Hub, event: LoggedEvent) -> Hub:
        p = event.payload
        comment = Comment(
            id=p["id"],
            author=hub.self_username,
            author_name=hub.self_name,
            body=p["body"],
            at=event.at,
            target_type=target_type,
            target_id=p[key],
        )
        return replace(hub, user_comments=(*hub.user_comments, comment))

    return Action(payload, decide, reduce, **where)


# --- pull requests -----------------------------------------------------------------------------


def decide_merge(hub: Hub, payload: dict) -> dict:
    existing_pr(hub, payload["pr_id"])
    state = hub.pr_state(payload["pr_id"])
    if state != "open":
        raise ActionRejected(f"pull request {payload['pr_id']!r} is {state}, not open", 409)
    return {"pr_id": payload["pr_id"], "strategy": payload.get("strategy", "merge")}


def reduce_merge(hub: Hub, event: LoggedEvent) -> Hub:
    pr_id = event.payload["pr_id"]
    if pr_id not in hub.prs or pr_id in hub.merged:
        return hub
    return with_items(replace(hub, merged=(*hub.merged, pr_id)), "pr_states", [(pr_id, "merged")])


# --- star, watch, fork ----------------------------------------------------------------------------

VERBS = {"starred": "starred", "watched": "watching", "forked": "forked"}


def flag_action(flag: str, counter: str, wanted: bool) -> Action[Hub]:
    """The button that sets the user's `flag` on the repository (set, not toggled) and moves
    `counter` by one; a request that changes nothing is a 409."""

    def decide(hub: Hub, payload: dict) -> dict:
        if getattr(hub, flag) == wanted:
            raise ActionRejected(
                f"you are {'already' if wanted else 'not'} {VERBS[flag]} {hub.owner}/{hub.name}",
                409,
            )
        return payload

    def reduce(hub: Hub, event: LoggedEvent) -> Hub:
        if getattr(hub, flag) == wanted:
            return hub
        return replace(
            hub, **{flag: wanted, counter: getattr(hub, counter) + (1 if wanted else -1)}
        )

    return Action(NoFields, decide, reduce, page=on(""))


# --- repositories -----------------------------------------------------------------------------


def check_repo_name(name: str) -> str:
    if not REPO_NAME.fullmatch(name):
        raise ActionRejected(
            "payload field 'name' may only contain letters, digits, '.', '-' and '_'"
        )
    return name


def decide_create_repository(hub: Hub, payload: dict) -> dict:
    name = check_repo_name(required_text(payload, "name"))
    if any(r.name.lower() == name.lower() for r in hub.user_repos):
        raise ActionRejected(f"you already have a repository named {name!r}", 409)
    return {**payload, "name": name, "id": f"user-repo-{len(hub.user_repos) + 1}"}


def reduce_create_repository(hub: Hub, event: LoggedEvent) -> Hub:
    p = event.payload
    repo = UserRepo(
        id=p["id"],
        name=p["name"],
        description=p.get("description", ""),
        visibility=p.get("visibility", "public"),
        owner=hub.self_username,
        created_at=event.at,
        commits=1 if p.get("add_readme") else 0,
    )
    return replace(hub, user_repos=(*hub.user_repos, repo))


def decide_settings(hub: Hub, payload: dict) -> dict:
    changes = {k: v for k, v in payload.items() if v is not None}
    if not changes:
        raise ActionRejected("give at least one of 'name', 'description', 'visibility'")
    if "name" in changes:
        check_repo_name(changes["name"].strip())
    return changes


def reduce_settings(hub: Hub, event: LoggedEvent) -> Hub:
    repo = {**hub.repo, **event.payload}
    if "visibility" in event.payload:
        repo["isPrivate"] = event.payload["visibility"] == "private"
    if "name" in event.payload:
        repo["fullName"] = f"{hub.owner}/{event.payload['name']}"
    return replace(hub, repo=MappingProxyType(repo))


def follow_action(following: bool) -> Action[Hub]:
    def decide(hub: Hub, payload: dict) -> dict:
        username = required_text(payload, "username")
        if username == hub.self_username:
            raise ActionRejected("you cannot follow yourself")
        if (username in hub.following) == following:
            raise ActionRejected(
                f"you {'already' if following else 'do not'} follow {username}", 409
            )
        return {"username": username}

    def reduce(hub: Hub, event: LoggedEvent) -> Hub:
        name = event.payload["username"]
        kept = tuple(u for u in hub.following if u != name)
        return replace(hub, following=(*kept, name) if following else kept)

    return Action(Username, decide, reduce, page=profile_page)


# --- where a person does it (Action.page); forms are marked data-action="<name>" ----------------


def issue_page(*fields: str) -> Callable[[Hub, dict], PageStep]:
    def page(hub: Hub, payload: dict) -> PageStep:
        existing_issue(hub, payload["issue_id"])
        return PageStep(f"issues/{payload['issue_id']}", {f: str(payload[f]) for f in fields})

    return page


def pr_page(*fields: str) -> Callable[[Hub, dict], PageStep]:
    def page(hub: Hub, payload: dict) -> PageStep:
        existing_pr(hub, payload["pr_id"])
        form = {f: str(payload[f]) for f in fields if f in payload}
        return PageStep(f"pulls/{payload['pr_id']}", form)

    return page


def on(path: str, *fields: str) -> Callable[[Hub, dict], PageStep]:
    def page(hub: Hub, payload: dict) -> PageStep:
        return PageStep(path, {f: str(payload.get(f, "")) for f in fields})

    return page


def new_repository_page(hub: Hub, payload: dict) -> PageStep:
    form = {
        "name": payload["name"],
        "description": payload.get("description", ""),
        "visibility": payload.get("visibility", "public"),
    }
    for box in ("add_readme", "add_gitignore"):
        if payload.get(box):
            form[box] = "on"
    return PageStep("new", form)


def settings_page(hub: Hub, payload: dict) -> PageStep:
    """Settings → General with the given fields changed (the others keep what they show)."""
    return PageStep("settings", {k: str(v) for k, v in payload.items() if v is not None})


def profile_page(hub: Hub, payload: dict) -> PageStep:
    return PageStep(f"users/{payload['username']}", {})


ACTIONS: Mapping[str, Action] = MappingProxyType(
    {
        "create_issue": Action(
            NewIssue,
            decide_create_issue,
            reduce_create_issue,
            page=on("issues/new", "title", "body"),
        ),
        "comment_issue": comment_action(
            "issue", IssueComment, help="Comment on an issue as the user.", page=issue_page("body")
        ),
        "close_issue": Action(
            IssueId, decide_set_state("closed"), set_issue(state="closed"), page=issue_page()
        ),
        "reopen_issue": Action(
            IssueId, decide_set_state("open"), set_issue(state="open"), page=issue_page()
        ),
        "view_issue": Action(
            IssueId,
            decide_view_issue,
            set_issue(viewed=True),
            help="Opening an issue marks it viewed (implicit).",
            page=lambda hub, p: PageStep(f"issues/{p['issue_id']}"),
        ),
        "comment_pr": comment_action("pr", PrComment, page=pr_page("body")),
        "merge_pr": Action(
            Merge,
            decide_merge,
            reduce_merge,
            help="Merge an open pull request (merge, squash or rebase).",
            page=pr_page("strategy"),
        ),
        "star": flag_action("starred", "star_offset", True),
        "unstar": flag_action("starred", "star_offset", False),
        "watch": flag_action("watched", "watchers", True),
        "unwatch": flag_action("watched", "watchers", False),
        # One way, as the original: a fork is not undone from here.
        "fork": flag_action("forked", "forks", True),
        "create_repository": Action(
            NewRepository,
            decide_create_repository,
            reduce_create_repository,
            page=new_repository_page,
        ),
        "update_repository": Action(
            RepositorySettings,
            decide_settings,
            reduce_settings,
            help="Settings → General: rename, describe, change visibility.",
            page=settings_page,
        ),
        "follow_user": follow_action(True),
        "unfollow_user": follow_action(False),
    }
)
