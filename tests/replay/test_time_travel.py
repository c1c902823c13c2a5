"""Time travel: the environment's own pages as of a log position, read-only, staff-only."""

from __future__ import annotations

import re

import pytest

from events.models import Event

pytestmark = pytest.mark.django_db

FLAGGED = "Unflag “Q3 budget review”"
NOT_FLAGGED = "Flag “Q3 budget review”"


def seq_of(run, kind, type) -> int:
    return Event.objects.get(run=run, kind=kind, type=type).seq


def page_at(client, run, seq, rest="") -> str:
    response = client.get(f"/admin/events/run/{run.pk}/at/{seq}/site/{rest}")
    assert response.status_code == 200
    return response.content.decode()


def rows(html: str) -> list[str]:
    return re.findall(r'name="ids" value="([^"]+)"', html)


def test_the_page_shows_exactly_the_mail_fired_up_to_that_position(finished_run, admin_client):
    arrival = seq_of(finished_run, "scenario", "new_email")
    before, after = (
        page_at(admin_client, finished_run, arrival - 1),
        page_at(admin_client, finished_run, arrival),
    )
    assert "late-report" not in rows(before)
    assert "late-report" in rows(after)
    assert "budget-review" in rows(before)


def test_flag_and_read_state_are_as_of_that_position(finished_run, admin_client):
    flag = seq_of(finished_run, "action", "flag")
    assert NOT_FLAGGED in page_at(admin_client, finished_run, flag - 1)
    assert FLAGGED in page_at(admin_client, finished_run, flag)
    opened = seq_of(finished_run, "action", "open_email")
    unread = re.compile(r'<li class="message unread">\s*<input[^>]*value="late-report"')
    assert unread.search(page_at(admin_client, finished_run, opened - 1))
    assert not unread.search(page_at(admin_client, finished_run, opened))


def test_time_travel_is_bannered_and_changes_nothing(finished_run, admin_client):
    count = Event.objects.filter(run=finished_run).count()
    opened = seq_of(finished_run, "action", "open_email")
    # Opening an unread message would mark it read on the live site; here it must not.
    html = page_at(admin_client, finished_run, opened - 1, "?folder=inbox&email=late-report")
    assert 'id="time-travel-banner"' in html and "Read-only" in html
    assert 'id="sentinel-live"' not in html
    assert Event.objects.filter(run=finished_run).count() == count
    post = admin_client.post(
        f"/admin/events/run/{finished_run.pk}/at/{opened}/site/emails/late-report/flag"
    )
    assert post.status_code == 405
    assert Event.objects.filter(run=finished_run).count() == count


def test_the_merged_timeline_links_every_row_to_its_moment(finished_run, admin_client):
    html = admin_client.get(f"/admin/events/run/{finished_run.pk}/timeline/").content.decode()
    assert (
        html.count("view the site at this moment") == Event.objects.filter(run=finished_run).count()
    )
    only_actions = admin_client.get(
        f"/admin/events/run/{finished_run.pk}/timeline/?kind=action"
    ).content.decode()
    assert (
        only_actions.count('class="kind-action"') == 2
        and 'class="kind-scenario"' not in only_actions
    )


def test_it_is_staff_only(finished_run, client):
    response = client.get(f"/admin/events/run/{finished_run.pk}/at/1/site/")
    assert response.status_code == 302 and "/admin/login/" in response["Location"]
    assert (
        client.get(
            f"/r/{finished_run.token}/admin/events/run/{finished_run.pk}/timeline/"
        ).status_code
        == 404
    )


def test_a_page_view_row_opens_the_page_the_agent_saw(finished_run, admin_client):
    from events.commands import record_view

    view = record_view(
        finished_run, f"/r/{finished_run.token}/micromail/?folder=inbox&email=late-report", at=0.0
    )
    html = admin_client.get(
        f"/admin/events/run/{finished_run.pk}/timeline/?kind=view"
    ).content.decode()
    assert (
        f"/admin/events/run/{finished_run.pk}/at/{view.seq}/site/?folder=inbox&amp;email=late-report"
        in html
    )
