"""What the calendar screens show, as pure functions of the calendar, the URL and today."""

from __future__ import annotations

from datetime import date

from apps.microlendar import screens
from apps.microlendar.query import CalendarQuery
from tests.microlendar.cast import act, preloaded

TODAY = date(2025, 9, 18)


def test_overlapping_events_sit_side_by_side_and_others_take_the_full_width():
    agenda = preloaded()
    screen = screens.calendar_screen(agenda, CalendarQuery(view="week", date="2025-09-22"), TODAY)
    monday = next(c for c in screen.columns if c.day == date(2025, 9, 22))
    placed = {b.chip.event.id: (b.left, b.width, b.top) for b in monday.blocks}
    assert placed == {"cf-01": (0.0, 50.0, 480), "cf-02": (50.0, 50.0, 504)}
    assert all(b.chip.conflict for b in monday.blocks)
    this_week = screens.calendar_screen(agenda, CalendarQuery(view="week"), TODAY)
    thursday = next(c for c in this_week.columns if c.day == TODAY)
    assert {(b.left, b.width) for b in thursday.blocks} == {(0.0, 100.0)}
    assert thursday.is_today and this_week.title == "September 2025"


def test_a_month_cell_shows_three_events_then_how_many_more():
    agenda = act(
        preloaded(), "create_event", {"title": "Extra", "date": "2025-09-18", "time": "18:00"}
    )
    screen = screens.calendar_screen(agenda, CalendarQuery(), TODAY)
    cell = next(c for week in screen.weeks for c in week if c.day == TODAY)
    assert [c.event.id for c in cell.chips] == ["td-01", "td-02", "td-03"]
    assert cell.more == 2 and cell.is_today
    assert screen.weeks[0][0].day == date(2025, 8, 31)  # the Sunday before the 1st


def test_hidden_calendars_leave_the_grid_and_the_count():
    agenda = preloaded()
    everything = screens.calendar_screen(agenda, CalendarQuery(), TODAY)
    no_personal = screens.calendar_screen(agenda, CalendarQuery(off="Personal"), TODAY)
    assert everything.count - no_personal.count == 1


def test_periods_titles_and_chevrons():
    agenda = preloaded()
    week = screens.calendar_screen(agenda, CalendarQuery(view="week", date="2025-09-30"), TODAY)
    assert week.title == "Sep – Oct 2025"
    assert week.previous_url == "?view=week&date=2025-09-23"
    day = screens.calendar_screen(agenda, CalendarQuery(view="day"), TODAY)
    assert day.title == "Thursday, September 18, 2025"
    assert day.next_url == "?view=day&date=2025-09-19"
    month = screens.calendar_screen(agenda, CalendarQuery(date="2025-01-31"), TODAY)
    assert month.previous_url == "?date=2024-12-31" and month.next_url == "?date=2025-02-28"


def test_search_matches_title_description_and_location():
    agenda = preloaded()
    found = screens.calendar_screen(agenda, CalendarQuery(q="ANALYTICS dashboard"), TODAY)
    assert [[c.event.id for c in chips] for _, chips in found.agenda] == [["desc-analytics-1"]]
    by_place = screens.calendar_screen(agenda, CalendarQuery(q="souvla"), TODAY)
    assert [c.event.id for _, chips in by_place.agenda for c in chips] == ["td-03"]


def test_the_task_list_puts_done_tasks_last_and_marks_overdue_ones():
    rows = screens.task_rows(preloaded(), TODAY)
    assert [r.id for r in rows] == ["tk-01", "tk-02", "tk-03"]
    assert rows[0].due == "Due Sep 19" and not rows[0].overdue
    assert rows[2].completed and not rows[2].overdue  # done: never overdue
    assert screens.task_rows(preloaded(), date(2025, 9, 20))[0].overdue
