"""MicroHub's events and actions on the state: preload, arrivals (numbering, 404 before they
arrive), the actions' checks and effects, and the evaluation tables' names and encodings."""

from __future__ import annotations

import sqlite3

import pytest

from apps.microhub.environment import BASELINES, MICROHUB
from apps.microhub.state import star_count
from events.registry import ActionRejected
from tests.microhub.cast import CAST, ME, PRELOAD, TOTP_ISSUE


def tables(hub, now: float = 200.0) -> sqlite3.Connection:
    conn = sqlite3.connect(":memory:")
    MICROHUB.materialize(hub, now, conn)
    return conn


def test_the_preload_loads_the_listed_rows_and_every_row_of_the_rest():
    hub = CAST.preloaded()
    assert list(hub.issues) == PRELOAD["issue_ids"]
    assert list(hub.prs) == ["pr1", "pr4"]
    assert len(hub.commits) == 25 and len(hub.runs) == 7
    assert len(hub.files) == 26  # file_ids defaults to ["*"]
    assert hub.issue_state("i8") == "closed"  # the catalog's state
    assert hub.pr_state("pr4") == "merged"


def test_a_preload_overrides_the_repository_counters_without_touching_the_catalog():
    hub = CAST.preloaded(
        initial_stars=10, initial_forks=3, default_branch="trunk", initial_commits=7
    )
    assert (star_count(hub, 0.0), hub.forks, hub.commit_total) == (1847, 3, 7)  # waypoints win
    assert hub.repo["branches"][0] == "trunk"
    fresh = CAST.preloaded()
    assert fresh.repo["defaultBranch"] == "main" and fresh.forks == 148


def test_a_filed_issue_is_numbered_after_every_issue_and_has_no_comments_yet():
    hub = CAST.preloaded()
    highest = max(i.number for i in hub.issues.values())
    hub = CAST.arrive(hub, "new_issue", {"issue_id": TOTP_ISSUE})
    issue = hub.issues[TOTP_ISSUE]
    assert issue.number == highest + 1 and issue.opened_at == 120.0
    assert hub.issue_state(TOTP_ISSUE) == "open"
    again = CAST.arrive(hub, "new_issue", {"issue_id": TOTP_ISSUE}, at=300.0)
    assert again is hub  # delivered twice: unchanged


def test_unknown_ids_change_nothing():
    hub = CAST.preloaded()
    for kind, payload in (
        ("new_issue", {"issue_id": "nope"}),
        ("new_pull_request", {"pr_id": "nope"}),
        ("new_commit", {"commit_id": "nope"}),
        ("new_workflow_run", {"run_id": "nope"}),
    ):
        assert CAST.arrive(hub, kind, payload) is hub


def test_pull_requests_commits_and_runs_arrive_first_in_their_lists():
    hub = CAST.preloaded()
    total = hub.commit_total
    hub = CAST.arrive(hub, "new_pull_request", {"pr_id": "pr5"}, at=150.0)
    hub = CAST.arrive(hub, "new_commit", {"commit_id": "c26"}, at=160.0)
    hub = CAST.arrive(hub, "new_workflow_run", {"run_id": "run-9"}, at=170.0)
    assert hub.prs["pr5"].number > max(i.number for i in hub.issues.values())
    assert next(iter(hub.commits)) == "c26" and hub.commit_total == total + 1
    assert next(iter(hub.runs)) == "run-9" and hub.runs["run-9"].at == 170.0


def test_a_comment_is_the_users_own_and_lands_in_user_created_comments():
    hub = CAST.act(CAST.preloaded(), "comment_issue", {"issue_id": "i1", "body": "On it"})
    rows = tables(hub).execute("SELECT id, target_type, target_id, body FROM user_created_comments")
    assert list(rows) == [("user-comment-1", "issue", "i1", "On it")]
    assert hub.user_comments[0].author == ME  # not the original's hard-coded author


@pytest.mark.parametrize(
    ("name", "payload", "status"),
    [
        ("comment_issue", {"issue_id": TOTP_ISSUE, "body": "x"}, 404),  # not filed yet
        ("comment_issue", {"issue_id": "i1", "body": "  "}, 400),
        ("merge_pr", {"pr_id": "pr4"}, 409),  # already merged
        ("close_issue", {"issue_id": "i8"}, 409),  # already closed
        ("unstar", {}, 409),
        ("create_issue", {"title": " "}, 400),
        ("create_repository", {"name": "has space"}, 400),
        ("follow_user", {"username": ME}, 400),
        ("update_repository", {}, 400),
    ],
)
def test_actions_refuse_what_the_state_does_not_allow(name, payload, status):
    with pytest.raises(ActionRejected) as refused:
        CAST.act(CAST.preloaded(), name, payload)
    assert refused.value.status == status


def test_close_reopen_merge_star_watch_fork_and_their_tables():
    hub = CAST.preloaded()
    hub = CAST.act(hub, "close_issue", {"issue_id": "i1"})
    hub = CAST.act(hub, "merge_pr", {"pr_id": "pr1", "strategy": "squash"})
    hub = CAST.act(hub, "star", {})
    hub = CAST.act(hub, "watch", {})
    hub = CAST.act(hub, "fork", {})
    conn = tables(hub)
    assert conn.execute("SELECT state FROM issue_states WHERE issue_id='i1'").fetchone() == (
        "closed",
    )
    assert conn.execute("SELECT state FROM issues WHERE id='i1'").fetchone() == (
        "open",
    )  # original
    assert list(conn.execute("SELECT pr_id FROM merged_prs")) == [("pr1",)]
    assert conn.execute("SELECT state FROM pr_states WHERE pr_id='pr1'").fetchone() == ("merged",)
    flags = dict(conn.execute("SELECT key, value FROM repo_flags"))
    assert flags == {
        "starred": "1",
        "watched": "1",
        "forked": "1",
        "star_count": str(star_count(hub, 200.0)),
        "fork_count": "149",
        "watch_count": "58",
    }
    with pytest.raises(ActionRejected):
        CAST.act(hub, "fork", {})  # one way


def test_a_created_issue_is_the_users_and_not_in_the_issues_table():
    hub = CAST.act(
        CAST.preloaded(), "create_issue", {"title": "Export boards as PDF", "body": "Please"}
    )
    issue = hub.user_issues["user-issue-1"]
    assert issue.number == max(i.number for i in hub.issues.values()) + 1
    conn = tables(hub)
    assert list(conn.execute("SELECT id, title, body FROM user_created_issues")) == [
        ("user-issue-1", "Export boards as PDF", "Please")
    ]
    assert conn.execute("SELECT COUNT(*) FROM issue_states").fetchone() == (4,)


def test_viewing_is_recorded_for_filed_issues_and_exported():
    hub = CAST.act(CAST.preloaded(), "view_issue", {"issue_id": "i3"})
    conn = tables(hub)
    assert conn.execute("SELECT isViewed FROM issue_states WHERE issue_id='i3'").fetchone() == (1,)
    assert conn.execute("SELECT isViewed FROM issue_states WHERE issue_id='i1'").fetchone() == (0,)


def test_settings_rename_and_visibility_reach_the_repository_table():
    hub = CAST.act(
        CAST.preloaded(), "update_repository", {"name": "tandem-web", "visibility": "private"}
    )
    repo = dict(tables(hub).execute("SELECT key, value FROM repository"))
    assert repo["name"] == "tandem-web" and repo["isPrivate"] == "True"
    assert repo["fullName"] == "mymicro/tandem-web"
    assert repo["stars"] == "1312"  # the original exported the catalog value here


def test_baselines_are_the_originals_names():
    hub = CAST.preloaded()
    measured = MICROHUB.measure_baselines(hub, 0.0)
    assert set(BASELINES) == {
        "star_count",
        "fork_count",
        "watch_count",
        "issue_count",
        "pr_count",
        "commit_count",
        "comment_count",
    }
    assert measured["star_count"] == 1847 and measured["issue_count"] == 4


def test_pass_through_tables_hold_json_rows():
    conn = tables(CAST.preloaded())
    (data,) = conn.execute("SELECT data FROM workflows WHERE id='wf-ci'").fetchone()
    assert '"CI"' in data
    assert conn.execute("SELECT COUNT(*) FROM runs").fetchone() == (7,)
    assert conn.execute("SELECT COUNT(*) FROM wiki").fetchone() == (0,)


def test_our_catalog_is_at_least_the_papers_size():
    """The paper's MicroHub: 20 issues, 12 pull requests, 25 commits, 26 files, 7 runs."""
    tables = CAST.preloaded().catalog.tables["microhub"]
    sizes = {name: len(tables[name]) for name in ("issues", "prs", "commits", "files")}
    sizes["workflow-runs"] = len(tables["workflow-runs"])
    assert sizes["issues"] >= 20 and sizes["prs"] >= 12 and sizes["commits"] >= 25
    assert sizes["files"] >= 26 and sizes["workflow-runs"] >= 7
    authors = {r["author"] for r in tables["issues"].values()}
    people = {u["username"] for u in CAST.preloaded().catalog.users.values()}
    assert authors <= people  # our shared personas, everywhere
