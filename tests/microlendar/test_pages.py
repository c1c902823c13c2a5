"""MicroLendar's pages through Django's test client: screens, forms, 404s and live regions."""

from __future__ import annotations

import re

import pytest

from events import lifecycle
from events.commands import current_state
from tests.microlendar.cast import LATE_AT, LATE_EVENT


def html(response) -> str:
    assert response.status_code == 200, response.content[:500]
    return response.content.decode()


@pytest.mark.parametrize("view", ["month", "week", "day", "4days", "schedule", "year"])
def test_every_view_renders_with_the_chrome_and_its_live_regions(browser, cal_url, view):
    page = html(browser.get(cal_url(f"?view={view}")))
    for region in ('id="calendar-view"', 'id="task-list"', 'id="mini-month"', 'id="event-count"'):
        assert region in page
    assert "Thu 18 Sep 09:00" in page  # the calendar's own simulated day, not the run's
    assert 'aria-current="date"' in page


def test_the_week_shows_todays_events_and_the_current_time_line(browser, cal_url):
    page = html(browser.get(cal_url("?view=week")))
    assert "Daily standup" in page and 'class="now-line" style="top:432px"' in page  # 9:00
    assert "Coffee with Hana" not in page  # added at t=60 only


def test_an_event_not_added_yet_is_a_404_then_shows_once_its_time_comes(
    browser, cal_url, calendar_run
):
    assert browser.get(cal_url(f"?event={LATE_EVENT}")).status_code == 404
    lifecycle.advance(calendar_run, LATE_AT)
    page = html(browser.get(cal_url(f"?view=day&event={LATE_EVENT}")))
    assert re.search(r'role="dialog"[^>]*aria-labelledby="details-title"', page)
    assert "Coffee with Hana" in page and "Saltmarsh Coffee, Valencia St" in page


def test_opening_details_marks_the_event_viewed_once(browser, cal_url, calendar_run):
    page = html(browser.get(cal_url("?view=week&date=2025-09-22&event=cf-02")))
    assert "Overlaps with Press briefing prep (10am)" in page
    assert "Rosa Delgado" in page and "Organizer" in page
    browser.get(cal_url("?view=week&date=2025-09-22&event=cf-02"))
    actions = [e.type for e in calendar_run.events.filter(kind="action")]
    assert actions == ["view_event"]
    assert current_state(calendar_run).event_states["cf-02"].viewed


@pytest.mark.parametrize("query", ["?view=fortnight", "?date=2025-02-30", "?off=Holidays"])
def test_a_bad_url_names_the_parameter(browser, cal_url, query):
    response = browser.get(cal_url(query))
    assert response.status_code in (400, 404)
    assert query.split("=")[0].lstrip("?") in response.content.decode()


def test_creating_an_event_through_the_form_returns_to_its_day(browser, cal_url, calendar_run):
    form = html(browser.get(cal_url("events/new?date=2025-09-19&time=15:00")))
    assert 'value="15:00"' in form and 'value="16:00"' in form
    response = browser.post(
        cal_url("events/new"),
        {
            "title": "Team trivia",
            "date": "2025-09-19",
            "time": "17:00",
            "endTime": "18:00",
            "calendar": "Family",
            "location": "",
            "description": "",
            "back": "view=week",
        },
    )
    assert response.status_code == 302 and response["Location"].endswith(
        "?view=week&date=2025-09-19"
    )
    agenda = current_state(calendar_run)
    assert agenda.events["user-event-1"].calendar == "Family"


def test_a_refused_form_comes_back_with_the_reason_and_the_typed_text(browser, cal_url):
    response = browser.post(
        cal_url("events/new"),
        {"title": "Team trivia", "date": "2025-09-19", "time": "17:00", "endTime": "16:00"},
    )
    assert response.status_code == 400
    page = response.content.decode()
    assert "endTime" in page and 'value="Team trivia"' in page


def test_editing_sends_only_what_changed(browser, cal_url, calendar_run):
    form = html(browser.get(cal_url("events/td-04/edit")))
    assert 'value="Interview: APM candidate"' in form
    browser.post(
        cal_url("events/td-04/edit"),
        {
            "title": "Interview: APM candidate",
            "date": "2025-09-18",
            "time": "14:00",
            "endTime": "15:00",
            "calendar": "Work",
            "location": "Zoom",
            "description": "Product sense round. Declan shares the scorecard after.",
        },
    )
    logged = calendar_run.events.get(kind="action")
    assert logged.type == "update_event" and logged.payload == {
        "event_id": "td-04",
        "location": "Zoom",
    }


def test_the_reschedule_form_and_a_drop_post_the_same_action(browser, cal_url, calendar_run):
    response = browser.post(
        cal_url("events/td-03/reschedule"),
        {"date": "2025-09-19", "time": "13:00", "back": "view=week"},
    )
    assert response.status_code == 302
    logged = calendar_run.events.get(kind="action")
    assert (logged.type, logged.payload) == (
        "reschedule_event",
        {"event_id": "td-03", "date": "2025-09-19", "time": "13:00", "endTime": "14:00"},
    )


def test_tasks_are_added_ticked_and_deleted_from_the_sidebar(browser, cal_url, calendar_run):
    browser.post(cal_url("tasks/new"), {"title": "Book venue", "dueDate": "2025-09-25"})
    browser.post(cal_url("tasks/tk-01/toggle"), {"task_id": "tk-01"})
    browser.post(cal_url("tasks/tk-02/delete"), {"task_id": "tk-02"})
    page = html(browser.get(cal_url()))
    assert "Book venue" in page and "Due Sep 25" in page
    assert re.search(r'aria-checked="true" aria-label="Draft sharing permissions spec"', page)
    assert "Send interview feedback" not in page


def test_deleting_an_event_closes_it(browser, cal_url):
    response = browser.post(cal_url("events/cf-01/delete"), {"back": "view=week&event=cf-01"})
    assert response["Location"].endswith("?view=week")
    assert browser.get(cal_url("?event=cf-01")).status_code == 404


def guest_list(page: str) -> list[tuple[str, str]]:
    """(name, what is written under it) per row of the open event's guest list."""
    rows = re.search(r'<ul aria-label="Guests">(.*?)</ul>', page, re.S)
    assert rows, "no guest list"
    return re.findall(r"<span[^>]*>([^<]+)<small>([^<]*)</small>", rows.group(1))


def test_an_invitation_names_whoever_sent_it_as_organizer_and_me_as_a_guest_awaiting(
    browser, cal_url, calendar_run
):
    lifecycle.advance(calendar_run, LATE_AT)
    page = html(browser.get(cal_url(f"?view=day&event={LATE_EVENT}")))
    assert guest_list(page) == [
        ("Hana Sato", "Organizer"),
        ("Chris Taylor", "Awaiting response"),
    ]
    assert "2 guests" in page and 'title="hsato@mymicromail.com"' in page


def test_an_invitation_there_from_the_start_was_accepted_and_my_own_event_is_mine(browser, cal_url):
    interview = html(browser.get(cal_url("?view=day&event=td-04")))
    assert guest_list(interview) == [
        ("Declan Rourke", "Organizer"),
        ("Chris Taylor", "Accepted"),
    ]
    lunch = html(browser.get(cal_url("?view=day&event=td-03")))
    assert guest_list(lunch)[0] == ("Chris Taylor", "Organizer")
