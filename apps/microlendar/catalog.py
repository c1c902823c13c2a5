"""Turning catalog records (SentinelBench format) into `CalendarEvent` and `Task` values.

One table, `microlendar/events.jsonl`, holds events and tasks alike (`is_task` tells them apart),
as upstream's does. A record: id, title, description, start_time / end_time (ISO), category
(Work, Family, Personal…), is_task, is_completed, attendees (user ids), location, order,
owner_id (whose calendar: always the self user). Our catalog may add `due_date` (YYYY-MM-DD) to
tasks, and `organizer` (a user id, or the address of someone outside the company) to an event
someone else invited the user to; upstream has neither: all its events are the user's own.
"""

from __future__ import annotations

from typing import Any

from apps.kit.arrivals import Stamp
from apps.kit.feeds import from_catalog
from apps.kit.records import Record, read
from apps.microlendar import times
from apps.microlendar.state import (
    CALENDARS,
    DAY_MIN,
    DEFAULT_CALENDAR,
    DEFAULT_DURATION_MIN,
    ENVIRONMENT,
    Agenda,
    Attendee,
    CalendarEvent,
    EventState,
    Task,
    TaskState,
)

TABLE = "events"


def attendee(catalog: Any, user_id: str) -> Attendee | None:
    user = catalog.users.get(str(user_id))
    if user is None:
        return None
    return read(Attendee, user, id=str(user_id), name=str(user.get("name") or user_id))


def organizer(catalog: Any, record: dict) -> Attendee | None:
    """Who invited the user to the event; None when it is their own. `owner_id` is the calendar
    the record is on (always the self user's), not who organises the event."""
    who = str(record.get("organizer") or "")
    self_id = (getattr(catalog, "self_user", None) or {}).get("id")
    if not who or who == self_id:
        return None
    # Someone not among the users (a school committee, a vendor): Google shows the bare address.
    return attendee(catalog, who) or Attendee(id=who, name=who, email=who)


@from_catalog(ENVIRONMENT, TABLE)
def catalog_event(
    agenda: Agenda, event_id: str, record: Record, stamp: Stamp
) -> tuple[CalendarEvent, EventState] | None:
    """The event `event_id`, marked as a new invitation unless it is part of the starting world;
    None if the catalog lacks it, it is a task or has no start time."""
    catalog = agenda.catalog
    if record.get("is_task") or not record.get("start_time"):
        return None
    day, start = times.parse_iso(record["start_time"])
    end = start + DEFAULT_DURATION_MIN
    if record.get("end_time"):
        end_day, end_minutes = times.parse_iso(record["end_time"])
        # An event running past midnight is shown up to the end of its first day.
        end = end_minutes if end_day == day else DAY_MIN
    if end <= start:
        end = start + DEFAULT_DURATION_MIN
    calendar = str(record.get("category") or DEFAULT_CALENDAR)
    people = (attendee(catalog, user_id) for user_id in record.get("attendees") or ())
    event = read(
        CalendarEvent,
        record,
        id=event_id,
        day=day,
        start=start,
        end=min(end, DAY_MIN),
        calendar=calendar if calendar in CALENDARS else DEFAULT_CALENDAR,
        attendees=tuple(p for p in people if p is not None),
        organizer=organizer(catalog, record),
        arrived_at=stamp.at,
    )
    return event, EventState(arrived_during_run=not stamp.preloaded)


@from_catalog(ENVIRONMENT, TABLE)
def catalog_task(
    agenda: Agenda, task_id: str, record: Record, stamp: Stamp
) -> tuple[Task, TaskState] | None:
    """The task `task_id` with its catalog completion; None if missing or not a task."""
    if not record.get("is_task"):
        return None
    due = record.get("due_date") or record.get("dueDate") or record.get("start_time")
    task = read(
        Task,
        record,
        id=task_id,
        due=times.parse_iso(due)[0] if due and "T" in str(due) else _date_or_none(due),
    )
    return task, read(TaskState, record)


def _date_or_none(text: Any):
    try:
        return times.parse_date(str(text)) if text else None
    except times.BadTime:
        return None
