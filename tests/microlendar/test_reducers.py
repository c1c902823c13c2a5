"""MicroLendar's scenario events, actions and baselines on the cast (tests/microlendar/cast.py)."""

from __future__ import annotations

import sqlite3
from datetime import date

import pytest

from apps.microlendar import state as agenda_state
from apps.microlendar.environment import MICROLENDAR
from events.registry import ActionRejected
from tests.microlendar.cast import CAST, PRELOADED, TASKS, act, preloaded


def tables(agenda) -> sqlite3.Connection:
    conn = sqlite3.connect(":memory:")
    MICROLENDAR.materialize(agenda, 0.0, conn)
    return conn


def test_the_preload_sets_the_days_and_delivers_events_and_tasks_in_order():
    agenda = preloaded()
    assert agenda.today == agenda.initial_date == date(2025, 9, 18)
    assert list(agenda.events) == PRELOADED
    assert list(agenda.tasks) == TASKS
    assert agenda.task_states["tk-03"].completed  # the catalog's is_completed is kept


def test_wildcards_split_the_one_catalog_table_into_events_and_tasks():
    agenda = preloaded(event_ids=["*"], task_ids=["*"])
    assert len(agenda.events) >= 57 and len(agenda.tasks) >= 10
    assert not set(agenda.events) & set(agenda.tasks)


def test_new_task_is_keyed_by_event_id_and_redelivery_changes_nothing():
    agenda = act(preloaded(), "delete_event", {"event_id": "td-01"})
    again = CAST.arrive(agenda, "new_event", {"event_id": "td-01"})
    assert again.event_states["td-01"].deleted  # upstream's re-fire un-deleted it
    with_task = CAST.arrive(agenda, "new_task", {"event_id": "tk-09"})
    assert "tk-09" in with_task.tasks
    unknown = CAST.arrive(agenda, "new_event", {"event_id": "nope"})
    assert unknown is agenda


def test_baselines_count_today_work_personal_tasks_and_overlapping_pairs():
    agenda = preloaded()
    baselines = MICROLENDAR.measure_baselines(agenda, 0.0)
    assert baselines["event_count"] == 7
    assert baselines["today_event_count"] == 4
    assert baselines["personal_event_count"] == 1  # lunch with Rosa
    assert baselines["work_event_count"] == 6
    assert baselines["task_count"] == 3
    assert baselines["conflict_count"] == 1  # cf-01 10:00-11:00 and cf-02 10:30-11:30


def test_opening_marks_viewed_and_the_events_table_shows_it():
    agenda = act(preloaded(), "view_event", {"event_id": "cf-02"})
    conn = tables(agenda)
    assert conn.execute("SELECT isViewed FROM event_states WHERE event_id='cf-02'").fetchone() == (
        1,
    )
    assert conn.execute("SELECT isViewed FROM event_states WHERE event_id='cf-01'").fetchone() == (
        0,
    )


def test_create_defaults_to_an_hour_at_nine_on_work_and_lands_in_user_created_events():
    agenda = act(preloaded(), "create_event", {"title": " Plan  offsite ", "date": "2025-09-18"})
    conn = tables(agenda)
    row = conn.execute("SELECT * FROM user_created_events").fetchone()
    assert row == ("user-event-1", "Plan offsite", "2025-09-18", "09:00", "10:00", "Work", 0)
    assert agenda_state.today_event_count(agenda) == 5


def test_a_reminder_in_the_afternoon_ends_after_it_starts():
    payload = {"title": "Call the bank", "date": "2025-09-19", "time": "15:00"}
    logged = MICROLENDAR.actions["create_event"].decide(preloaded(), payload)
    assert (logged["time"], logged["endTime"]) == ("15:00", "16:00")


@pytest.mark.parametrize(
    "payload, message",
    [
        ({"title": "x", "date": "2025-13-01"}, "date '2025-13-01' is not a calendar date"),
        ({"title": "x", "date": "18/09/2025"}, "is not a date like 2025-09-18"),
        ({"title": "x", "date": "2025-09-18", "time": "9am"}, "time '9am' is not a time"),
        ({"title": "x", "date": "2025-09-18", "time": "10:00", "endTime": "09:00"}, "endTime"),
        ({"title": "  ", "date": "2025-09-18"}, "'title' must not be empty"),
    ],
)
def test_bad_event_input_is_refused_naming_the_field(payload, message):
    with pytest.raises(ActionRejected, match=message):
        MICROLENDAR.actions["create_event"].decide(preloaded(), payload)


def test_reschedule_keeps_the_length_and_reaches_the_events_table():
    agenda = act(
        preloaded(),
        "reschedule_event",
        {"event_id": "td-02", "date": "2025-09-22", "time": "14:15"},
    )
    event = agenda.events["td-02"]
    assert (event.day, event.start, event.end) == (date(2025, 9, 22), 14 * 60 + 15, 15 * 60)
    row = (
        tables(agenda)
        .execute("SELECT start_time, end_time FROM events WHERE id='td-02'")
        .fetchone()
    )
    assert row == ("2025-09-22T14:15:00Z", "2025-09-22T15:00:00Z")


def test_reschedule_without_a_time_moves_the_date_only():
    logged = MICROLENDAR.actions["reschedule_event"].decide(
        preloaded(), {"event_id": "td-01", "date": "2025-09-25"}
    )
    assert logged == {
        "event_id": "td-01",
        "date": "2025-09-25",
        "time": "09:30",
        "endTime": "09:45",
    }


def test_edit_changes_only_the_fields_given_and_a_new_start_keeps_the_length():
    agenda = act(
        preloaded(),
        "update_event",
        {"event_id": "td-04", "title": "Interview: PM", "time": "16:00"},
    )
    event = agenda.events["td-04"]
    assert (event.title, event.start, event.end, event.location) == (
        "Interview: PM",
        16 * 60,
        17 * 60,
        "Tandem HQ · Room Twin Peaks",
    )


def test_deleted_events_are_404_for_every_action_and_leave_the_counts():
    agenda = act(preloaded(), "delete_event", {"event_id": "cf-01"})
    assert agenda_state.conflict_count(agenda) == 0
    with pytest.raises(ActionRejected) as refused:
        MICROLENDAR.actions["view_event"].decide(agenda, {"event_id": "cf-01"})
    assert refused.value.status == 404
    assert tables(agenda).execute(
        "SELECT deleted FROM event_states WHERE event_id='cf-01'"
    ).fetchone() == (1,)


def test_toggling_a_task_logs_the_completion_it_leads_to():
    agenda = preloaded()
    logged = MICROLENDAR.actions["toggle_task"].decide(agenda, {"task_id": "tk-03"})
    assert logged == {"task_id": "tk-03", "completed": False}
    agenda = act(agenda, "toggle_task", {"task_id": "tk-01"})
    rows = dict(tables(agenda).execute("SELECT task_id, completed FROM task_states").fetchall())
    assert rows == {"tk-01": 1, "tk-02": 0, "tk-03": 1}


def test_created_tasks_count_with_catalog_tasks_and_deleted_ones_do_not():
    agenda = act(preloaded(), "create_task", {"title": "Prep demo", "dueDate": "2025-09-20"})
    agenda = act(agenda, "delete_task", {"task_id": "tk-02"})
    conn = tables(agenda)
    assert conn.execute("SELECT * FROM user_created_tasks").fetchall() == [
        ("user-task-1", "Prep demo", "2025-09-20", 0, 0)
    ]
    assert agenda_state.task_count(agenda) == 3
    assert conn.execute("SELECT dueDate FROM tasks WHERE id='tk-01'").fetchone() == ("2025-09-19",)


def test_an_invitation_from_outside_the_company_names_its_organizer_by_address():
    agenda = CAST.arrive(preloaded(), "new_event", {"event_id": "clash-04"})
    bake_sale = agenda.events["clash-04"]  # from the school's parents' committee
    assert bake_sale.organizer is not None
    assert bake_sale.organizer.name == bake_sale.organizer.email == "bakesale@rosewoodparents.org"
    assert [(g.person.name, g.note) for g in agenda_state.guests(agenda, bake_sale)] == [
        ("bakesale@rosewoodparents.org", "Organizer"),
        ("Chris Taylor", "Awaiting response"),
    ]


def test_an_event_of_the_users_own_names_them_organizer_and_lists_the_attendees_after():
    agenda = preloaded()
    guests = agenda_state.guests(agenda, agenda.events["td-01"])  # the standup Chris runs
    assert guests[0].person.name == "Chris Taylor" and guests[0].note == "Organizer"
    assert [g.person.name for g in guests[1:]] == [a.name for a in agenda.events["td-01"].attendees]
