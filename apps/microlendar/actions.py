"""What an agent can do to the calendar: `Action(schema, decide, reduce, page)` per action name.

`decide(agenda, payload)` checks the request against the current calendar and returns the
payload to log, completed with what it decided (a generated id, defaulted times, the end kept
by a reschedule, the new completion of a toggled task), so that `reduce` only copies logged
values: it trusts the log and never raises, and replay is deterministic.
"""

from __future__ import annotations

from collections.abc import Mapping
from datetime import date
from types import MappingProxyType
from typing import Literal
from urllib.parse import urlencode

from pydantic import Field

from apps.kit.deciding import marking
from apps.kit.fields import ItemId, Line, Moment, Text
from apps.kit.state import setting, with_changed
from apps.kit.streaming import id_payload
from apps.microlendar import times
from apps.microlendar.query import CalendarQuery
from apps.microlendar.state import (
    CALENDARS,
    DAY_MIN,
    DEFAULT_CALENDAR,
    DEFAULT_DURATION_MIN,
    Agenda,
    CalendarEvent,
    EventState,
    Task,
    TaskState,
    with_created,
)
from events.registry import Action, ActionRejected, LoggedEvent, PageStep
from events.schemas import Payload

DEFAULT_START = "09:00"  # upstream's defaults for a new event
# An event's fields as logged and as its form names them (upstream's) → the attribute each sets,
# how its text is read, and how the attribute is written back.
EVENT_FIELDS = {
    "title": ("title", str, str),
    "date": ("day", times.parse_date, date.isoformat),
    "time": ("start", times.parse_clock, times.hhmm),
    "endTime": ("end", times.parse_clock, times.hhmm),
    "calendar": ("calendar", str, str),
    "description": ("description", str, str),
    "location": ("location", str, str),
}


EventId = id_payload("EventId", "event_id", "id of an event on the calendar")


class EventDetails(Payload):
    """A new event; upstream's field names (times "HH:MM", calendar Work/Family/Personal/Tasks)."""

    title: Line
    date: Moment = Field(description="YYYY-MM-DD")
    time: Moment | None = Field(None, description="start, HH:MM (default 09:00)")
    endTime: Moment | None = Field(None, description="end, HH:MM (default an hour after the start)")
    calendar: Literal[CALENDARS] | None = None
    description: Text | None = None
    location: Line | None = None


class EventChanges(Payload):
    """An edit: any of the fields; null is the same as leaving a field out."""

    event_id: ItemId
    title: Line | None = None
    date: Moment | None = Field(None, description="YYYY-MM-DD")
    time: Moment | None = Field(None, description="HH:MM")
    endTime: Moment | None = Field(None, description="HH:MM")
    calendar: Literal[CALENDARS] | None = None
    description: Text | None = None
    location: Line | None = None


class Reschedule(Payload):
    """Move an event (the form or a drag and drop): new date, optionally a new start; the
    duration is kept."""

    event_id: ItemId
    date: Moment = Field(description="YYYY-MM-DD")
    time: Moment | None = Field(None, description="new start, HH:MM (default: unchanged)")


class NewTask(Payload):
    title: Line
    dueDate: Moment | None = Field(None, description="YYYY-MM-DD")


TaskId = id_payload("TaskId", "task_id", "id of a task in the list")


def existing_event(agenda: Agenda, event_id: str) -> CalendarEvent:
    """The event, or a 404: unknown, deleted and not-yet-added ids look the same."""
    if not agenda.has_event(event_id):
        raise ActionRejected(f"no event {event_id!r} on this calendar", status=404)
    return agenda.events[event_id]


def existing_task(agenda: Agenda, task_id: str) -> Task:
    if not agenda.has_task(task_id):
        raise ActionRejected(f"no task {task_id!r} in the task list", status=404)
    return agenda.tasks[task_id]


def naming(existing, key: str):
    """A decide() whose one rule is that `payload[key]` names an item `existing` finds."""

    def decide(agenda: Agenda, payload: dict) -> dict:
        existing(agenda, payload[key])
        return payload

    return decide


def _read(parse, text: str, field: str):
    try:
        return parse(text, field=field)
    except times.BadTime as exc:
        raise ActionRejected(f"payload field {exc}") from None


def _title(text: str) -> str:
    title = " ".join(text.split())
    if not title:
        raise ActionRejected("payload field 'title' must not be empty")
    return title


def _times(start_text: str, end_text: str | None) -> tuple[str, str]:
    """("HH:MM", "HH:MM") with the end after the start; a missing end is an hour later
    (upstream always defaulted it to 10:00, giving afternoon reminders a negative length)."""
    start = _read(times.parse_clock, start_text, "time")
    if end_text:
        end = _read(times.parse_clock, end_text, "endTime")
        if end <= start:
            raise ActionRejected(
                f"payload field 'endTime' {end_text!r} must be after the start {start_text!r}"
            )
    else:
        end = min(start + DEFAULT_DURATION_MIN, DAY_MIN - 1)
    return times.hhmm(start), times.hhmm(end)


# --- events ----------------------------------------------------------------------------------------


def event_fields(logged: Mapping) -> dict:
    """The event's attributes a logged create or edit sets (an edit logs only what changed)."""
    return {
        attr: read(logged[name]) for name, (attr, read, _) in EVENT_FIELDS.items() if name in logged
    }


def decide_view(agenda: Agenda, payload: dict) -> dict:
    if existing_event(agenda, payload["event_id"]).user_created:
        raise ActionRejected(
            f"event {payload['event_id']!r} is one you created: only invitations are tracked as viewed"
        )
    return payload


def decide_create(agenda: Agenda, payload: dict) -> dict:
    day = _read(times.parse_date, payload["date"], "date")
    start, end = _times(payload.get("time") or DEFAULT_START, payload.get("endTime"))
    return {
        "id": f"user-event-{agenda.created_count('event') + 1}",  # upstream's id shape
        "title": _title(payload["title"]),
        "date": day.isoformat(),
        "time": start,
        "endTime": end,
        "calendar": payload.get("calendar") or DEFAULT_CALENDAR,
        "description": payload.get("description") or "",
        "location": payload.get("location") or "",
    }


def reduce_create(agenda: Agenda, event: LoggedEvent) -> Agenda:
    created = CalendarEvent(
        id=event.payload["id"], **event_fields(event.payload), user_created=True
    )
    return with_created(agenda, "event", created, EventState())


def decide_update(agenda: Agenda, payload: dict) -> dict:
    """Fields left out (or null) keep their value; the result must still be a valid event."""
    current = existing_event(agenda, payload["event_id"])
    changes = {k: payload[k] for k in EVENT_FIELDS if payload.get(k) is not None}
    if "title" in changes:
        changes["title"] = _title(changes["title"])
    if "date" in changes:
        changes["date"] = _read(times.parse_date, changes["date"], "date").isoformat()
    if "time" in changes or "endTime" in changes:
        start = changes.get("time") or times.hhmm(current.start)
        end = changes.get("endTime") or times.hhmm(current.end)
        if "endTime" not in changes:  # a new start alone keeps the duration
            end = times.hhmm(
                min(_read(times.parse_clock, start, "time") + current.duration, DAY_MIN - 1)
            )
        changes["time"], changes["endTime"] = _times(start, end)
    if not changes:
        raise ActionRejected("an edit needs at least one of: " + ", ".join(EVENT_FIELDS))
    return {"event_id": payload["event_id"], **changes}


def reduce_update(agenda: Agenda, event: LoggedEvent) -> Agenda:
    return with_changed(agenda, "events", event.payload["event_id"], **event_fields(event.payload))


def decide_reschedule(agenda: Agenda, payload: dict) -> dict:
    """Logged as {event_id, date, time, endTime} whether it came from the form or a drag."""
    current = existing_event(agenda, payload["event_id"])
    day = _read(times.parse_date, payload["date"], "date")
    start = (
        _read(times.parse_clock, payload["time"], "time") if payload.get("time") else current.start
    )
    start = min(start, DAY_MIN - current.duration)  # the event still ends on its day
    return {
        "event_id": current.id,
        "date": day.isoformat(),
        "time": times.hhmm(start),
        "endTime": times.hhmm(start + current.duration),
    }


# --- tasks -----------------------------------------------------------------------------------------


def decide_create_task(agenda: Agenda, payload: dict) -> dict:
    due = payload.get("dueDate")
    return {
        "id": f"user-task-{agenda.created_count('task') + 1}",
        "title": _title(payload["title"]),
        "dueDate": _read(times.parse_date, due, "dueDate").isoformat() if due else None,
    }


def reduce_create_task(agenda: Agenda, event: LoggedEvent) -> Agenda:
    p = event.payload
    due = times.parse_date(p["dueDate"]) if p.get("dueDate") else None
    task = Task(id=p["id"], title=p["title"], due=due, user_created=True)
    return with_created(agenda, "task", task, TaskState())


def decide_toggle_task(agenda: Agenda, payload: dict) -> dict:
    """Logs the completion the toggle leads to, so replaying it twice cannot flip it back."""
    task_id = existing_task(agenda, payload["task_id"]).id
    return {"task_id": task_id, "completed": not agenda.task_states[task_id].completed}


def reduce_toggle_task(agenda: Agenda, event: LoggedEvent) -> Agenda:
    completed = bool(event.payload["completed"])
    return with_changed(agenda, "task_states", event.payload["task_id"], completed=completed)


# --- where a person does it (Action.page) -----------------------------------------------------
# Forms and buttons are marked `data-action="<action>"` in the templates; the generic tests carry
# out every scenario's solution through them (tests/environments/).


def details_screen(agenda: Agenda, event_id: str) -> str:
    """The day of the event with its details open: `?view=day&date=<day>&event=<id>`."""
    event = existing_event(agenda, event_id)
    return CalendarQuery(view="day", date=event.day.isoformat()).with_item("event", event_id)


def view_page(agenda: Agenda, payload: dict) -> PageStep:
    """Opening the details is the action (an implicit action of the calendar page)."""
    return PageStep(details_screen(agenda, payload["event_id"]))


def typed(payload: dict, fields) -> dict[str, str]:
    """The form values a person types: the payload's `fields` that are given."""
    return {name: str(payload[name]) for name in fields if payload.get(name) is not None}


def details_form(*fields: str):
    def page(agenda: Agenda, payload: dict) -> PageStep:
        return PageStep(details_screen(agenda, payload["event_id"]), typed(payload, fields))

    return page


def create_page(agenda: Agenda, payload: dict) -> PageStep:
    on_day = urlencode({"date": payload["date"]})
    return PageStep(f"events/new?{on_day}", typed(payload, EVENT_FIELDS))


def edit_page(agenda: Agenda, payload: dict) -> PageStep:
    existing_event(agenda, payload["event_id"])
    return PageStep(f"events/{payload['event_id']}/edit", typed(payload, EVENT_FIELDS))


def task_list(*fields: str):
    """The task list beside the calendar, with `fields` of the payload typed in."""

    def page(agenda: Agenda, payload: dict) -> PageStep:
        return PageStep("", {name: str(payload[name]) for name in fields if payload.get(name)})

    return page


# Deleting only marks an item deleted (its id stays taken; the evaluation tables keep its row).
marks_event = marking(EventId, naming(existing_event, "event_id"), "event_states", "event_id")
marks_task = marking(TaskId, naming(existing_task, "task_id"), "task_states", "task_id")

ACTIONS: Mapping[str, Action] = MappingProxyType(
    {
        "view_event": Action(
            EventId,
            decide_view,
            setting("event_states", "event_id", viewed=True),
            help="Open an event's details (marks an invitation viewed).",
            page=view_page,
        ),
        "create_event": Action(
            EventDetails,
            decide_create,
            reduce_create,
            help="Create an event (reminders are events in Personal described 'Reminder').",
            page=create_page,
        ),
        "update_event": Action(
            EventChanges,
            decide_update,
            reduce_update,
            help="Edit any of an event's fields.",
            page=edit_page,
        ),
        "reschedule_event": Action(
            Reschedule,
            decide_reschedule,
            reduce_update,
            help="Move an event to another date and start, keeping its length (form or drag).",
            page=details_form("date", "time"),
        ),
        "delete_event": marks_event(deleted=True, page=details_form()),
        "create_task": Action(
            NewTask, decide_create_task, reduce_create_task, page=task_list("title", "dueDate")
        ),
        "toggle_task": Action(
            TaskId,
            decide_toggle_task,
            reduce_toggle_task,
            help="Tick or untick a task.",
            page=task_list("task_id"),
        ),
        "delete_task": marks_task(deleted=True, page=task_list("task_id")),
    }
)
