"""MicroLendar's registration with the core: scenario events, baselines, evaluation tables.

Scenario events (SentinelBench format; events and tasks share the catalog table `events`):
- `preload_events {today, initial_date, event_ids, task_ids}` — the calendar the task starts
  from (`["*"]` = every event, resp. every task, of the catalog). Baselines are measured right
  after it.
- `new_event {event_id}` — one event appears on the calendar.
- `new_task {event_id}` — one task appears in the task list (upstream keys it `event_id`).
"""

from __future__ import annotations

import sqlite3
from collections.abc import Mapping
from dataclasses import replace
from types import MappingProxyType

from pydantic import Field

from apps.kit.legacy_tables import Table
from apps.microlendar import state as agenda_state
from apps.microlendar import times
from apps.microlendar.actions import ACTIONS
from apps.microlendar.bench import sample_pages
from apps.microlendar.catalog import catalog_event, catalog_task, event_ids, task_ids
from apps.microlendar.state import ENVIRONMENT, Agenda, empty_agenda, with_events, with_tasks
from events.registry import Environment, EventType, ImplicitAction, LoggedEvent, Measure, timeless
from events.schemas import Payload

DATE_PATTERN = r"^\d{4}-\d{2}-\d{2}$"

# Counted right after the preload, by the core (upstream's names: eval_sql reads baseline_<name>).
BASELINES: Mapping[str, Measure] = MappingProxyType(
    {
        name: timeless(count)
        for name, count in {
            "event_count": agenda_state.event_count,
            "today_event_count": agenda_state.today_event_count,
            "work_event_count": agenda_state.work_event_count,
            "task_count": agenda_state.task_count,
            "personal_event_count": agenda_state.personal_event_count,
            "conflict_count": agenda_state.conflict_count,
        }.items()
    }
)


def deliver_events(agenda: Agenda, ids: list[str]) -> Agenda:
    """Put catalog events on the calendar. An id already there is left as it is (upstream
    appended a duplicate and reset its state, which could un-delete it); ids missing from the
    catalog, and tasks, are skipped."""
    arrivals = []
    for event_id in dict.fromkeys(ids):
        if event_id in agenda.events:
            continue
        event = catalog_event(agenda.catalog, event_id)
        if event is not None:
            arrivals.append(event)
    return with_events(agenda, arrivals) if arrivals else agenda


def deliver_tasks(agenda: Agenda, ids: list[str]) -> Agenda:
    arrivals = []
    for task_id in dict.fromkeys(ids):
        if task_id in agenda.tasks:
            continue
        task = catalog_task(agenda.catalog, task_id)
        if task is not None:
            arrivals.append(task)
    return with_tasks(agenda, arrivals) if arrivals else agenda


def reduce_preload_events(agenda: Agenda, event: LoggedEvent) -> Agenda:
    p = event.payload
    dated = replace(
        agenda,
        today=times.parse_date(p["today"]) if p.get("today") else agenda.today,
        initial_date=(
            times.parse_date(p["initial_date"]) if p.get("initial_date") else agenda.initial_date
        ),
    )
    dated = deliver_events(dated, event_ids(agenda.catalog, list(p.get("event_ids") or [])))
    return deliver_tasks(dated, task_ids(agenda.catalog, list(p.get("task_ids") or [])))


def reduce_new_event(agenda: Agenda, event: LoggedEvent) -> Agenda:
    return deliver_events(agenda, [event.payload["event_id"]])


def reduce_new_task(agenda: Agenda, event: LoggedEvent) -> Agenda:
    return deliver_tasks(agenda, [event.payload["event_id"]])


class PreloadEvents(Payload):
    today: str | None = Field(None, pattern=DATE_PATTERN, description="YYYY-MM-DD")
    initial_date: str | None = Field(None, pattern=DATE_PATTERN, description="YYYY-MM-DD")
    event_ids: list[str] = Field([], description='catalog event ids; ["*"] = every event')
    task_ids: list[str] = Field([], description='catalog task ids; ["*"] = every task')


class NewEvent(Payload):
    event_id: str = Field(description="catalog event id")


class NewTask(Payload):
    event_id: str = Field(description="catalog task id (upstream's key name)")


EVENT_TYPES: Mapping[str, EventType] = MappingProxyType(
    {
        "preload_events": EventType(
            schema=PreloadEvents,
            reduce=reduce_preload_events,
            help="The calendar at the start (today, the day shown first, events, tasks); "
            "baselines are measured after it.",
            catalog_refs={"event_ids": "events", "task_ids": "events"},
            preload=True,
        ),
        "new_event": EventType(
            schema=NewEvent,
            reduce=reduce_new_event,
            help="One event appears on the calendar.",
            catalog_refs={"event_id": "events"},
        ),
        "new_task": EventType(
            schema=NewTask,
            reduce=reduce_new_task,
            help="One task appears in the task list.",
            catalog_refs={"event_id": "events"},
        ),
    }
)


# --- evaluation tables (upstream names and columns, so eval_sql runs unchanged) -----------------

EVENTS = Table(
    "events",
    (
        "id TEXT PRIMARY KEY",
        "title TEXT",
        "start_time TEXT",
        "end_time TEXT",
        "category TEXT",
        "is_task INTEGER",
        "description TEXT",
    ),
)
EVENT_STATES = Table(
    "event_states", ("event_id TEXT PRIMARY KEY", "deleted INTEGER", "isViewed INTEGER")
)
TASKS = Table("tasks", ("id TEXT PRIMARY KEY", "title TEXT", "dueDate TEXT"))
TASK_STATES = Table(
    "task_states", ("task_id TEXT PRIMARY KEY", "completed INTEGER", "deleted INTEGER")
)
USER_CREATED_EVENTS = Table(
    "user_created_events",
    (
        "id TEXT PRIMARY KEY",
        "title TEXT",
        "date TEXT",
        "time TEXT",
        "endTime TEXT",
        "calendar TEXT",
        "deleted INTEGER",
    ),
)
USER_CREATED_TASKS = Table(
    "user_created_tasks",
    (
        "id TEXT PRIMARY KEY",
        "title TEXT",
        "dueDate TEXT",
        "completed INTEGER",
        "deleted INTEGER",
    ),
)


def materialize(agenda: Agenda, now: float, conn: sqlite3.Connection) -> None:
    """Write the six tables (nothing on a calendar moves between events: `now` is unused).

    Catalog events show their current title, times, calendar and description (upstream kept the
    rows as loaded, so edits never reached eval_sql; no original eval_sql depends on that).
    Catalog tasks carry their due date when the catalog gives one (upstream: always NULL).
    """
    catalog_events = [e for e in agenda.events.values() if not e.user_created]
    user_events = [e for e in agenda.events.values() if e.user_created]
    EVENTS.write(
        conn,
        (
            (
                e.id,
                e.title,
                times.iso(e.day, e.start),
                times.iso(e.day, e.end),
                e.calendar,
                False,
                e.description,
            )
            for e in catalog_events
        ),
    )
    EVENT_STATES.write(
        conn,
        (
            (e.id, agenda.event_states[e.id].deleted, agenda.event_states[e.id].viewed)
            for e in catalog_events
        ),
    )
    USER_CREATED_EVENTS.write(
        conn,
        (
            (
                e.id,
                e.title,
                e.day.isoformat(),
                times.hhmm(e.start),
                times.hhmm(e.end),
                e.calendar,
                agenda.event_states[e.id].deleted,
            )
            for e in user_events
        ),
    )
    catalog_tasks = [t for t in agenda.tasks.values() if not t.user_created]
    TASKS.write(conn, ((t.id, t.title, _due(t)) for t in catalog_tasks))
    TASK_STATES.write(
        conn,
        (
            (t.id, agenda.task_states[t.id].completed, agenda.task_states[t.id].deleted)
            for t in catalog_tasks
        ),
    )
    USER_CREATED_TASKS.write(
        conn,
        (
            (
                t.id,
                t.title,
                _due(t),
                agenda.task_states[t.id].completed,
                agenda.task_states[t.id].deleted,
            )
            for t in agenda.tasks.values()
            if t.user_created
        ),
    )


def _due(task) -> str | None:
    return task.due.isoformat() if task.due else None


MICROLENDAR = Environment(
    name=ENVIRONMENT,
    title="MicroLendar",
    initial_state=empty_agenda,
    event_types=EVENT_TYPES,
    actions=ACTIONS,
    baselines=BASELINES,
    materialize=materialize,
    urlconf="apps.microlendar.urls",
    implicit_actions=(
        # Opening an event's details marks it viewed (upstream had a /view endpoint its page
        # never called, §6; the original's "open each event" eval_sql reads isViewed).
        ImplicitAction(
            page="calendar",
            param="event",
            action="view_event",
            payload=lambda event_id: {"event_id": event_id},
            applies=lambda agenda, event_id: (
                agenda.has_event(event_id)
                and not agenda.events[event_id].user_created
                and not agenda.event_states[event_id].viewed
            ),
        ),
    ),
    sample_pages=sample_pages,
)
