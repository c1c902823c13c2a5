"""What an agent sends cannot grow its own run's log without bound (finding: every GET logged its
full URL, ≈15 KB each)."""

from __future__ import annotations

import pytest
from django.test import Client

from apps.kit.fields import TEXT_CHARS
from apps.kit.links import environment_root
from apps.scenarios.library import get_scenario
from events import lifecycle
from events.commands import VIEW_PATH_LIMIT
from events.evaluation import evaluate
from events.models import Event, EventKind

pytestmark = pytest.mark.django_db


def test_a_viewed_url_is_logged_up_to_the_limit_and_says_how_long_it_was():
    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    url = f"{environment_root(run)}/?q={'x' * 15_000}"
    assert Client().get(url).status_code == 200
    view = Event.objects.filter(run=run, kind=EventKind.VIEW).latest("seq")
    assert view.payload["path"] == url[:VIEW_PATH_LIMIT]
    assert view.payload["path_length"] == len(url)


def test_an_ordinary_url_is_logged_whole():
    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    url = f"{environment_root(run)}/?folder=inbox"
    assert Client().get(url).status_code == 200
    view = Event.objects.filter(run=run, kind=EventKind.VIEW).latest("seq")
    assert view.payload["path"] == url and "path_length" not in view.payload


def test_an_agent_that_has_used_its_log_budget_is_refused_and_its_views_go_unlogged(settings):
    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    logged = Event.objects.filter(run=run).count()  # the preload
    settings.SENTINEL_AGENT_LOG_BUDGET = logged - len(run.timeline) + 2  # two more entries
    client = Client()
    inbox = f"{environment_root(run)}/?folder=inbox"
    assert client.get(inbox).status_code == 200  # logged: one left
    act = {"action": "mark_read", "payload": {"email_id": "base-04"}}
    assert client.post(f"/r/{run.token}/actions", act, "application/json").status_code == 201
    refused = client.post(f"/r/{run.token}/actions", act, "application/json")
    assert refused.status_code == 429 and "SENTINEL_AGENT_LOG_BUDGET" in refused.json()["detail"]
    assert client.get(inbox).status_code == 200  # the page still shows
    assert Event.objects.filter(run=run).count() == logged + 2


def test_an_agent_that_has_stored_its_bytes_is_refused_however_few_its_entries(settings):
    """Maximal texts: each action within its field's bound, a few hundred of them ≈ 20 MB."""
    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    settings.SENTINEL_AGENT_BYTES_BUDGET = 120_000
    client = Client()
    draft = {"action": "save_draft", "payload": {"to": ["a@example.com"], "subject": "s"}}
    sent = []
    for _ in range(4):
        draft["payload"]["body"] = "x" * 50_000  # the most a mail body may hold
        sent.append(client.post(f"/r/{run.token}/actions", draft, "application/json"))
    assert [r.status_code for r in sent[:3]] == [201, 201, 201]
    assert sent[3].status_code == 429
    assert "SENTINEL_AGENT_BYTES_BUDGET" in sent[3].json()["detail"]
    stored = Event.objects.filter(run=run, kind=EventKind.ACTION).count()
    assert stored == 3  # the refused one is not logged


def test_the_bytes_an_agent_stored_are_the_same_from_the_cache_and_from_scratch():
    from events.projection import fold_from_scratch, folded_state

    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    client = Client()
    client.get(f"{environment_root(run)}/?folder=inbox")
    act = {"action": "mark_read", "payload": {"email_id": "base-04"}}
    assert client.post(f"/r/{run.token}/actions", act, "application/json").status_code == 201
    acted = folded_state(run).agent_bytes
    assert acted > 0 and acted == fold_from_scratch(run).agent_bytes
    assert client.post(f"/r/{run.token}/contact", {"message": "done"}).status_code == 200
    cached = folded_state(run).agent_bytes
    assert cached == acted + len('{"message": "done"}') == fold_from_scratch(run).agent_bytes


def test_a_contact_at_the_start_is_its_own_runs_bytes_not_a_shared_openings():
    """Runs of one scenario share the fold of their log's opening (the preload at 0 s); a
    contact before the clock starts is logged at 0 s too, and is counted for its run alone."""
    from events.projection import clear_cache, folded_state

    spec = get_scenario("micromail-inbox-relative-passive").to_run_spec()
    talkative, quiet = lifecycle.create_run(spec), lifecycle.create_run(spec)
    Client().post(f"/r/{talkative.token}/contact", {"message": "x" * 1000})
    Client().post(f"/r/{quiet.token}/contact", {"message": ""})
    clear_cache()
    assert folded_state(talkative).agent_bytes > 1000
    assert folded_state(quiet).agent_bytes < 100


def test_a_contact_message_is_bounded_as_every_free_text(settings):
    """The audit's break: the contact form's message had no bound (3 × 2 MB were stored)."""
    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    client, contact = Client(), f"/r/{run.token}/contact"
    refused = client.post(contact, {"message": "x" * (TEXT_CHARS + 1)})
    assert refused.status_code == 400
    detail = refused.json()["detail"]
    assert f"'message' must have at most {TEXT_CHARS} characters" in detail and "\n" not in detail
    assert not Event.objects.filter(run=run, type__startswith="contact").exists()
    run.refresh_from_db()
    assert run.status != "completed"  # refused before it counted: the agent can send it again
    assert client.post(contact, {"message": "x" * TEXT_CHARS}).status_code == 200


def test_contacts_count_against_the_runs_bytes_budget(settings):
    """The audit's break: contacts were outside the budgets (with 1,000 bytes allowed, three
    contacts of 2 MB each were stored)."""
    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    settings.SENTINEL_AGENT_BYTES_BUDGET = 120_000
    client, contact = Client(), f"/r/{run.token}/contact"
    sent = [client.post(contact, {"message": "x" * TEXT_CHARS}) for _ in range(4)]
    assert [r.status_code for r in sent[:3]] == [200, 200, 200]
    assert sent[3].status_code == 429
    assert "SENTINEL_AGENT_BYTES_BUDGET" in sent[3].json()["detail"]
    assert "contacts" in sent[3].json()["detail"]
    assert Event.objects.filter(run=run, type="contact_post").count() == 3
    # Spent by contacts, the budget refuses actions too: one budget for all the agent writes.
    act = {"action": "mark_read", "payload": {"email_id": "base-04"}}
    assert client.post(f"/r/{run.token}/actions", act, "application/json").status_code == 429


def test_contacts_count_against_the_runs_entry_budget(settings):
    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    logged = Event.objects.filter(run=run).count()
    settings.SENTINEL_AGENT_LOG_BUDGET = logged - len(run.timeline) + 1  # one more entry
    client, contact = Client(), f"/r/{run.token}/contact"
    assert client.get(contact).status_code == 200  # the first contact: graded as ever
    refused = client.get(contact)
    assert refused.status_code == 429
    assert "SENTINEL_AGENT_LOG_BUDGET" in refused.json()["detail"]
    assert client.post(contact, {"message": "again"}).status_code == 429
    assert Event.objects.filter(run=run).count() == logged + 1
    verdict = evaluate(run)
    assert verdict.contact_get_time is not None and verdict.contact_message is None


def huge_log(run, entries: int) -> None:
    """`entries` page views appended to the run's log at once (as an agent looping would)."""
    first = Event.objects.filter(run=run).count() + 1
    Event.objects.bulk_create(
        Event(
            run=run,
            seq=seq,
            at=1.0,
            kind=EventKind.VIEW,
            type="page",
            payload={"path": "/viewed-again-and-again"},
            recorded_at=0.0,
        )
        for seq in range(first, first + entries)
    )


def test_a_huge_run_renders_in_the_admin_a_page_at_a_time(
    admin_client, django_assert_max_num_queries
):
    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    huge_log(run, 1_200)
    total = Event.objects.filter(run=run).count()
    change = admin_client.get(f"/admin/events/run/{run.pk}/change/").content.decode()
    assert f"{total:,} entries" in change and "viewed-again-and-again" not in change
    timeline = f"/admin/events/run/{run.pk}/timeline/"
    with django_assert_max_num_queries(20):  # as for a small run: no query per entry
        first = admin_client.get(timeline).content.decode()
    assert first.count('class="time-travel"') == 500
    assert f"entries 1–500 of {total}" in first and "page=2" in first
    last = admin_client.get(f"{timeline}?page=3").content.decode()
    assert last.count('class="time-travel"') == total - 1000
    only_actions = admin_client.get(f"{timeline}?kind=action").content.decode()
    assert "timeline-pages" not in only_actions  # one page: no pager


def test_a_runs_log_comes_a_page_at_a_time_in_order(monkeypatch):
    from rest_framework.test import APIClient

    from apps.control import pagination

    run = lifecycle.create_run(get_scenario("micromail-inbox-relative-passive").to_run_spec())
    huge_log(run, 25)
    total = Event.objects.filter(run=run).count()
    api, seqs, sizes = APIClient(), [], []
    url = f"/api/runs/{run.pk}/events/?limit=10"
    while url:
        page = api.get(url)
        assert page.status_code == 200
        sizes.append(len(page.json()))
        seqs += [row["seq"] for row in page.json()]
        url = page.get("Link", "").split(">")[0].strip("<")
    assert seqs == list(range(1, total + 1))
    assert max(sizes) == 10 and all(size == 10 for size in sizes[:-1])  # never more than asked
    assert "Link" not in api.get(f"/api/runs/{run.pk}/events/").headers  # all in one page
    assert api.get(f"/api/runs/{run.pk}/events/?after=x").status_code == 400
    # Unasked, a page holds LOG_PAGE entries, and no one may ask for more than LOG_MOST.
    monkeypatch.setattr(pagination, "LOG_PAGE", 7)
    monkeypatch.setattr(pagination, "LOG_MOST", 12)
    first = api.get(f"/api/runs/{run.pk}/events/")
    assert len(first.json()) == 7 and "after=7" in first["Link"]
    assert api.get(f"/api/runs/{run.pk}/events/?limit=13").status_code == 400
