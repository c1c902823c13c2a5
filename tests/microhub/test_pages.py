"""MicroHub's pages: every screen renders in the shell with its live regions, an item not yet
arrived is a 404, the forms perform their actions, and what opening an issue does."""

from __future__ import annotations

import re

import pytest

from apps.microhub.bench import sample_pages
from events import lifecycle
from events.commands import current_state

pytestmark = pytest.mark.django_db


def html(response) -> str:
    assert response.status_code == 200, response.content[:500]
    return response.content.decode()


def test_every_sample_page_renders_in_the_shell(client, hub_run, hub_url):
    lifecycle.advance(hub_run, 200.0)
    for path in sample_pages(current_state(hub_run)):
        text = html(client.get(hub_url(path)))
        assert 'id="main"' in text and "mymicro" in text, path


def test_the_repository_page_shows_counts_files_and_the_readme(client, hub_url):
    text = html(client.get(hub_url()))
    assert 'id="star-count"' in text and ">1,847<" in text
    assert "Watch" in text and "Fork" in text and "148" in text
    assert 'aria-label="open issues">3<' in text  # i1, i3, i12 (i8 is closed)
    assert ">README.md<" in text and "<h1>Tandem</h1>" in text
    assert "2,186</strong> Commits" in text


def test_every_link_of_the_readme_opens_a_page_of_the_repository(client, hub_url):
    """Finding: the README's links to docs/ led to a bare 404."""
    text = html(client.get(hub_url()))
    readme = text[text.index("<h1>Tandem</h1>") :]
    links = re.findall(r'href="(/r/[^"]+/blob/[^"]+)"', readme)
    assert any(link.endswith("/blob/docs/api.md") for link in links)
    for link in links:
        assert client.get(link).status_code == 200, link


def test_items_are_404_until_they_arrive_then_listed(client, hub_run, hub_url):
    for path in ("issues/i14", "pulls/pr5", "actions/runs/run-9"):
        assert client.get(hub_url(path)).status_code == 404
    assert "Two-factor authentication" not in html(client.get(hub_url("issues/")))
    lifecycle.advance(hub_run, 200.0)
    listing = html(client.get(hub_url("issues/")))
    assert "Two-factor authentication: support authenticator apps" in listing
    assert "opened 1 minute ago" in listing  # filed at 120, seen at 200
    for path in ("issues/i14", "pulls/pr5", "actions/runs/run-9"):
        assert client.get(hub_url(path)).status_code == 200


def test_issue_list_filters_state_search_and_sort(client, hub_url):
    closed = html(client.get(hub_url("issues/?state=closed")))
    assert "Upgrade CI runners to Node 22" in closed and "Sync stalls" not in closed
    found = html(client.get(hub_url("issues/?q=spinner")))  # in i1's body only
    assert "Sync stalls when two devices" in found and "Board view" not in found
    assert client.get(hub_url("issues/?sort=sideways")).status_code == 400


def test_opening_an_issue_marks_it_viewed_once(client, hub_run, hub_url):
    text = html(client.get(hub_url("issues/i1")))
    assert "Steps to reproduce</h2>" in text and "<ol><li>Open the same list" in text
    assert current_state(hub_run).issue_states["i1"].viewed
    client.get(hub_url("issues/i1"))
    assert hub_run.events.filter(kind="action", type="view_issue").count() == 1


def test_commenting_and_closing_through_the_issue_page(client, hub_run, hub_url):
    response = client.post(hub_url("issues/i3/comment"), {"body": "Same on **Safari**"})
    assert response.status_code == 302
    text = html(client.get(hub_url("issues/i3")))
    assert "<strong>Safari</strong>" in text and "ctaylor" in text
    client.post(hub_url("issues/i3/close"))
    assert current_state(hub_run).issue_state("i3") == "closed"
    assert "Reopen issue" in html(client.get(hub_url("issues/i3")))


def test_new_issue_form_creates_and_opens_it(client, hub_run, hub_url):
    assert 'data-action="create_issue"' in html(client.get(hub_url("issues/new")))
    response = client.post(hub_url("issues/new"), {"title": "Dark mode for email digests"})
    assert response.status_code == 302 and response["Location"].endswith("issues/user-issue-1")
    assert "Dark mode for email digests" in html(client.get(hub_url("issues/user-issue-1")))


def test_merging_a_pull_request_through_its_page(client, hub_run, hub_url):
    page = html(client.get(hub_url("pulls/pr1")))
    assert 'data-action="merge_pr"' in page and "Squash and merge" in page
    client.post(hub_url("pulls/pr1/merge"), {"strategy": "rebase"})
    assert current_state(hub_run).pr_state("pr1") == "merged"
    merged = html(client.get(hub_url("pulls/?state=closed")))
    assert "feat: offline queue drains" in merged and "was merged" in merged


def test_star_button_toggles_and_the_count_moves_by_one(client, hub_url):
    client.post(hub_url("repo/star"), {"back": "issues/"})
    text = html(client.get(hub_url()))
    assert ">1,848<" in text and "Starred" in text and 'data-action="unstar"' in text
    client.post(hub_url("repo/unstar"))
    assert ">1,847<" in html(client.get(hub_url()))


def test_a_refused_action_names_the_reason(client, hub_url):
    client.post(hub_url("repo/fork"))
    refused = client.post(hub_url("repo/fork"))
    assert refused.status_code == 409 and b"already forked" in refused.content


def test_new_repository_settings_and_profile_forms(client, hub_run, hub_url):
    client.post(
        hub_url("new"), {"name": "retro-notes", "visibility": "private", "add_readme": "on"}
    )
    assert "retro-notes" in html(client.get(hub_url("repositories/")))
    client.post(
        hub_url("settings"),
        {"name": "tandem", "description": "Boards for teams", "visibility": "public"},
    )
    assert current_state(hub_run).repo["description"] == "Boards for teams"
    profile = html(client.get(hub_url("users/dvolsky")))
    assert "Dmitri Volsky" in profile and 'data-action="follow_user"' in profile
    client.post(hub_url("users/dvolsky"))
    assert current_state(hub_run).following == ("dvolsky",)


def test_folders_files_commits_and_actions(client, hub_run, hub_url):
    folder = html(client.get(hub_url("tree/sync")))
    assert "resolver.go" in folder and "queue.go" in folder
    blob = html(client.get(hub_url("blob/sync/queue.go")))
    assert "Queue holds edits made offline" in blob
    assert client.get(hub_url("tree/nope")).status_code == 404
    commits = html(client.get(hub_url("commits/")))
    assert "fix(sync): skip tombstoned cards" in commits
    actions = html(client.get(hub_url("actions/?workflow=wf-release")))
    assert "chore(release): v3.4.1" in actions and "Release" in actions


def test_the_owner_is_an_organization_page_and_unknown_people_are_404(client, hub_url):
    org = html(client.get(hub_url("users/mymicro")))
    assert "MyMicro Inc." in org and "tandem" in org
    assert client.get(hub_url("users/nobody")).status_code == 404
