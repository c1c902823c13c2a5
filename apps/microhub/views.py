"""MicroHub pages: thin views over `page.state` (screens.py says what each shows), actions
through `page.act`, post/redirect/get back to the screen the form was on.

Every repository page shows the star count, which moves with the clock: `repo_header`
reads it at `page.now` and registers when it next changes, so a kept or live page is never
stale. Opening an issue marks it viewed: declared with the environment (`implicit_actions`).
"""

from __future__ import annotations

import posixpath

from django.http import Http404, HttpRequest, HttpResponse
from django.views.decorators.http import require_http_methods

from apps.kit.pages import AGE_REFRESH_S, Page, form_view, one_of, run_page, screen_view
from apps.kit.rendering import back_field, redirect_after, redirect_to, render_screen
from apps.kit.streaming import present
from apps.microhub import screens
from apps.microhub.markup import render_markdown
from apps.microhub.query import ActionsQuery, IssuesQuery, PullsQuery
from apps.microhub.state import MERGE_STRATEGIES, Hub, star_count, stars_change_at

REPO_ACTIONS = ("star", "unstar", "watch", "unwatch", "fork")
ISSUE_ACTIONS = {"comment": "comment_issue", "close": "close_issue", "reopen": "reopen_issue"}
PR_ACTIONS = {"comment": "comment_pr", "merge": "merge_pr"}
FORM_FIELDS = {"comment": ("body", ""), "merge": ("strategy", "merge")}  # → (field, default)
STRATEGY_LABELS = {
    "merge": "Create a merge commit",
    "squash": "Squash and merge",
    "rebase": "Rebase and merge",
}


def repo_header(page: Page) -> dict:
    """The repository header every repository page shows: names, counters, the tab badges."""
    hub: Hub = page.state
    # GitHub shows the star count as of the page's load. Here the slow drift between waypoints
    # reaches an open page with the clock's next minute (one push for both), never star by star;
    # a burst of stars is an event of the run's log, and every event is pushed at once.
    page.refreshes_at(stars_change_at(hub, page.now), AGE_REFRESH_S)
    return {
        "hub": hub,
        "me": hub.self_username,
        "me_name": hub.self_name,
        "stars": star_count(hub, page.now),
        "counts": screens.counts(hub),
    }


def show(page: Page, template: str, tab: str, **context) -> HttpResponse:
    context = {**repo_header(page), "tab": tab, **context}
    return render_screen(page.request, page, f"microhub/{template}", context)


# --- code -----------------------------------------------------------------------------------------


@screen_view
def code(request: HttpRequest, page: Page, path: str = "") -> HttpResponse:
    hub = page.state
    if path:
        folder = screens.file_at(hub, path)
        if folder is None or not folder.is_folder:
            raise Http404("no such folder")
    readme = screens.readme(hub, path)
    return show(
        page,
        "code.html",
        "code",
        path=path,
        crumbs=crumbs(path),
        entries=screens.folder_entries(hub, path),
        readme=readme,
        readme_html=render_markdown(readme.content, files_of(page, path)) if readme else "",
        latest=screens.latest_commit(hub),
        contributors=screens.contributors(hub)[:12],
    )


def files_of(page: Page, folder: str) -> str:
    """The blob URL of a folder: a Markdown file's relative links are resolved in it."""
    return f"{page.root}/blob/{folder}"


def crumbs(path: str) -> list[tuple[str, str]]:
    """(name, path) of each folder on the way to `path`."""
    parts = path.split("/") if path else []
    return [(part, "/".join(parts[: k + 1])) for k, part in enumerate(parts)]


@screen_view
def blob(request: HttpRequest, page: Page, path: str) -> HttpResponse:
    found = screens.file_at(page.state, path)
    if found is None or found.is_folder:
        raise Http404("no such file")
    markdown = found.name.lower().endswith(".md")
    return show(
        page,
        "blob.html",
        "code",
        file=found,
        crumbs=crumbs(path),
        rendered=render_markdown(found.content, files_of(page, posixpath.dirname(path)))
        if markdown
        else "",
        lines=found.content.split("\n"),
    )


@screen_view
def commits(request: HttpRequest, page: Page) -> HttpResponse:
    return show(page, "commits.html", "code", history=screens.commit_history(page.state))


# --- issues ---------------------------------------------------------------------------------------


@screen_view
def issues(request: HttpRequest, page: Page) -> HttpResponse:
    query = IssuesQuery.from_params(request.GET)
    hub = page.state
    open_count, closed_count = screens.search_counts(hub, query.q)
    return show(
        page,
        "issues.html",
        "issues",
        query=query,
        rows=screens.issue_rows(hub, query.state, query.q, query.sort),
        open_count=open_count,
        closed_count=closed_count,
        open_url=query.but(state="open").querystring(),
        closed_url=query.but(state="closed").querystring(),
        sorts=[(s, query.but(sort=s).querystring()) for s in ("newest", "oldest", "comments")],
    )


@require_http_methods(["GET", "POST"])
@run_page
def new_issue(request: HttpRequest, page: Page) -> HttpResponse:
    if request.method == "POST":
        event = page.act("create_issue", posted(request, "title", "body"))
        issue_id = event.payload["id"] if event else ""
        return redirect_to(page, f"issues/{issue_id}" if issue_id else "issues/")
    return show(page, "new_issue.html", "issues")


@screen_view
def issue(request: HttpRequest, page: Page, issue_id: str) -> HttpResponse:
    hub = page.state
    found = present(hub.issue(issue_id), "issue")  # unknown or not filed yet: alike
    return show(
        page,
        "issue.html",
        "issues",
        issue=found,
        state=hub.issue_state(issue_id),
        thread=screens.comments_on(hub, "issue", issue_id),
        body_html=render_markdown(found.body) if found.body else "",
    )


def posted(request: HttpRequest, *fields: str) -> dict[str, str]:
    """The form's `fields` as posted ("" when missing)."""
    return {field: request.POST.get(field, "") for field in fields}


def act_on_post(
    page: Page, verb: str, actions: dict[str, str], what: str, key: str, item_id: str
) -> None:
    """Carry out the button `verb` (one of `actions`) of the issue or pull request `{key: item_id}`,
    with the field its form posts (FORM_FIELDS)."""
    action = actions[one_of(verb, actions, what)]
    payload = {key: item_id}
    if verb in FORM_FIELDS:
        field, default = FORM_FIELDS[verb]
        payload[field] = page.request.POST.get(field, default)
    page.act(action, payload)


@form_view
def issue_action(request: HttpRequest, page: Page, issue_id: str, verb: str) -> HttpResponse:
    act_on_post(page, verb, ISSUE_ACTIONS, "issue action", "issue_id", issue_id)
    return redirect_to(page, f"issues/{issue_id}")


# --- pull requests ----------------------------------------------------------------------------------


@screen_view
def pulls(request: HttpRequest, page: Page) -> HttpResponse:
    query = PullsQuery.from_params(request.GET)
    return show(
        page, "pulls.html", "pulls", query=query, rows=screens.pr_rows(page.state, query.state)
    )


@screen_view
def pull(request: HttpRequest, page: Page, pr_id: str) -> HttpResponse:
    hub = page.state
    pr = present(hub.prs.get(pr_id), "pull request")
    return show(
        page,
        "pull.html",
        "pulls",
        pr=pr,
        state=hub.pr_state(pr_id),
        thread=screens.comments_on(hub, "pr", pr_id),
        body_html=render_markdown(pr.body) if pr.body else "",
        strategies=[(s, STRATEGY_LABELS[s]) for s in MERGE_STRATEGIES],
    )


@form_view
def pull_action(request: HttpRequest, page: Page, pr_id: str, verb: str) -> HttpResponse:
    act_on_post(page, verb, PR_ACTIONS, "pull request action", "pr_id", pr_id)
    return redirect_after(
        request,
        page,
        f"pulls/{pr_id}",
        "Pull request successfully merged and closed" if verb == "merge" else "",
    )


# --- actions ----------------------------------------------------------------------------------------


@screen_view
def actions(request: HttpRequest, page: Page) -> HttpResponse:
    query = ActionsQuery.from_params(request.GET)
    hub = page.state
    return show(
        page,
        "actions.html",
        "actions",
        query=query,
        runs=screens.workflow_runs(hub, query.workflow),
        workflows=screens.workflows(hub),
    )


@screen_view
def run(request: HttpRequest, page: Page, run_id: str) -> HttpResponse:
    found = present(page.state.runs.get(run_id), "workflow run")
    return show(page, "run.html", "actions", run=found)


# --- the repository's buttons, settings, the user's repositories and profiles -------------------


@form_view
def repo_action(request: HttpRequest, page: Page, verb: str) -> HttpResponse:
    page.act(one_of(verb, REPO_ACTIONS, "action"), {})
    return redirect_to(page, back_field(request))


@require_http_methods(["GET", "POST"])
@run_page
def settings(request: HttpRequest, page: Page) -> HttpResponse:
    if request.method == "POST":
        changes = {
            name: request.POST[name].strip()
            for name in ("name", "description", "visibility")
            if name in request.POST
            and request.POST[name].strip() != str(page.state.repo.get(name, ""))
        }
        if "visibility" in changes and changes["visibility"] == page.state.visibility:
            del changes["visibility"]
        page.act("update_repository", changes)
        return redirect_after(request, page, "settings", "Repository settings saved")
    return show(page, "settings.html", "settings")


@require_http_methods(["GET", "POST"])
@run_page
def new_repository(request: HttpRequest, page: Page) -> HttpResponse:
    if request.method == "POST":
        form = posted(request, "name", "description")
        form["visibility"] = request.POST.get("visibility", "public")
        boxes = {box: box in request.POST for box in ("add_readme", "add_gitignore")}
        page.act("create_repository", {**form, **boxes})
        return redirect_after(request, page, "repositories/", "Repository created")
    return show(page, "new_repository.html", "")


@screen_view
def repositories(request: HttpRequest, page: Page) -> HttpResponse:
    return show(page, "repositories.html", "", repos=page.state.user_repos)


@require_http_methods(["GET", "POST"])
@run_page
def profile(request: HttpRequest, page: Page, username: str) -> HttpResponse:
    hub = page.state
    person = next((u for u in hub.catalog.users.values() if u.get("username") == username), None)
    if person is None and username == hub.owner:
        return show(page, "organization.html", "", org=screens.organization(hub))
    if person is None:
        raise Http404("no such user")
    if request.method == "POST":
        verb = "unfollow_user" if username in hub.following else "follow_user"
        page.act(verb, {"username": username})
        return redirect_to(page, f"users/{username}")
    return show(
        page,
        "profile.html",
        "",
        person=person,
        is_self=username == hub.self_username,
        following=username in hub.following,
        activity=screens.person_activity(hub, username),
        repos=hub.user_repos if username == hub.self_username else (),
    )
