"""MicroLendar's registration with the core: scenario events, baselines, evaluation tables.

Scenario events (SentinelBench format; events and tasks share the catalog table `events`):
- `preload_events {today, initial_date, event_ids, task_ids}` — the calendar the task starts
  from (`["*"]` = every event, resp. every task, of the catalog). Baselines are measured right
  after it.
- `new_event {event_id}` — one event appears on the calendar.
- `new_task {event_id}` — one task appears in the task list (upstream keys it `event_id`).
- `cancel_event {event_id}` — its organiser cancels an event: it leaves the calendar, its counts
  and the new invitations, as Google Calendar removes a cancelled event from its guests'
  calendars; its details, if open, say "This event has been canceled" (apps.kit.retractions).

An id already delivered is left as it is (upstream appended a duplicate and reset its state,
which could un-delete it); ids missing from the catalog, tasks given as events and events given
as tasks are skipped (so `["*"]` splits the one table into events and tasks).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace
from functools import partial
from typing import Any, NamedTuple

from pydantic import Field

from apps.kit.arrivals import Delivery, arrival, event_types, preload
from apps.kit.counts import ShownCount, untimed
from apps.kit.deciding import opening
from apps.kit.environments import declare
from apps.kit.retractions import retraction, window
from apps.kit.tables import Rows, Table, named, tables
from apps.microlendar import state as agenda_state
from apps.microlendar import times
from apps.microlendar.catalog import catalog_event, catalog_task
from apps.microlendar.state import ENVIRONMENT, Agenda, empty_agenda
from events.registry import counted
from events.schemas import Payload

DATE_PATTERN = r"^\d{4}-\d{2}-\d{2}$"

# Counted right after the preload, by the core (upstream's names: eval_sql reads baseline_<name>).
BASELINES = counted(
    {
        "event_count": agenda_state.event_count,
        "today_event_count": agenda_state.today_event_count,
        "work_event_count": partial(agenda_state.calendar_event_count, calendar="Work"),
        "task_count": agenda_state.task_count,
        "personal_event_count": partial(agenda_state.calendar_event_count, calendar="Personal"),
        "conflict_count": agenda_state.conflict_count,
    }
)


deliver_events = Delivery("events", catalog_event, states="event_states")
deliver_tasks = Delivery("tasks", catalog_task, states="task_states")  # with their completion


class CalendarDays(Payload):
    """The preload's days: what "today" means for the baselines, and the day the UI opens on."""

    today: str | None = Field(None, pattern=DATE_PATTERN, description="YYYY-MM-DD")
    initial_date: str | None = Field(None, pattern=DATE_PATTERN, description="YYYY-MM-DD")


def set_days(agenda: Agenda, payload: Mapping[str, Any], at: float) -> Agenda:
    """The preload's `today` and `initial_date`, where given."""
    days = {
        name: times.parse_date(payload[name])
        for name in CalendarDays.model_fields
        if payload.get(name)
    }
    return replace(agenda, **days)


EVENT_TYPES = event_types(
    preload(
        "preload_events",
        {"event_ids": ("events", deliver_events), "task_ids": ("events", deliver_tasks)},
        base=CalendarDays,
        then=set_days,
        environment=ENVIRONMENT,
        help="The calendar at the start (today, the day shown first, events, tasks); "
        "baselines are measured after it.",
    ),
    arrival(
        "new_event", "event_id", "events", deliver_events, help="One event appears on the calendar."
    ),
    arrival(
        "new_task",
        "event_id",
        "events",
        deliver_tasks,
        help="One task appears in the task list.",
        description="catalog task id (upstream's key name)",
    ),
    retraction(
        "cancel_event",
        "event_id",
        "events",
        "events",
        help="Its organiser cancels an event: it leaves the calendar (open, its details say it "
        "was cancelled).",
    ),
)


# --- evaluation tables (upstream names and columns, so eval_sql runs unchanged) -----------------
# Nothing on a calendar moves between events: `now` is unused. Catalog events show their current
# title, times, calendar and description (upstream kept the rows as loaded, so edits never
# reached eval_sql; no original eval_sql depends on that). Catalog tasks carry their due date
# when the catalog gives one (upstream: always NULL). What the user created has tables of its own.


class Entry(NamedTuple):
    """A row: an event (or task), whose attributes it reads as its own, and its state."""

    item: Any
    state: Any

    def __getattr__(self, name: str) -> Any:  # only called for what the row itself lacks
        return getattr(self.item, name)


def entries(kind: str, *, user_created: bool) -> Rows[Agenda]:
    """The catalog's (or the user's) `kind`s ("event", "task") with their states, in order."""

    def rows(agenda: Agenda, now: float):
        states = getattr(agenda, f"{kind}_states")
        items = getattr(agenda, f"{kind}s").values()
        return (Entry(i, states[i.id]) for i in items if i.user_created == user_created)

    return rows


def due(task: Entry) -> str | None:
    return task.due.isoformat() if task.due else None


CATALOG_EVENTS, USER_EVENTS = (entries("event", user_created=mine) for mine in (False, True))
CATALOG_TASKS, USER_TASKS = (entries("task", user_created=mine) for mine in (False, True))
# Columns several tables share.
ITEM = named("id TEXT PRIMARY KEY", "title TEXT")
COMPLETED = {"completed INTEGER": "state.completed"}
DELETED = {"deleted INTEGER": "state.deleted"}

materialize = tables(
    Table(
        "events",
        CATALOG_EVENTS,
        {
            **ITEM,
            "start_time TEXT": lambda event: times.iso(event.day, event.start),
            "end_time TEXT": lambda event: times.iso(event.day, event.end),
            "category TEXT": "calendar",
            "is_task INTEGER": lambda event: False,
            **named("description TEXT"),
            **window("arrived_at"),
        },
    ),
    Table(
        "event_states",
        CATALOG_EVENTS,
        {"event_id TEXT PRIMARY KEY": "id", **DELETED, "isViewed INTEGER": "state.viewed"},
    ),
    Table(
        "user_created_events",
        USER_EVENTS,
        {
            **ITEM,
            "date TEXT": lambda event: event.day.isoformat(),
            "time TEXT": lambda event: times.hhmm(event.start),
            "endTime TEXT": lambda event: times.hhmm(event.end),
            **named("calendar TEXT"),
            **DELETED,
        },
    ),
    Table("tasks", CATALOG_TASKS, {**ITEM, "dueDate TEXT": due}),
    Table("task_states", CATALOG_TASKS, {"task_id TEXT PRIMARY KEY": "id", **COMPLETED, **DELETED}),
    Table("user_created_tasks", USER_TASKS, {**ITEM, "dueDate TEXT": due, **COMPLETED, **DELETED}),
)


def unviewed_invitation(agenda: Agenda, event_id: str) -> bool:
    return (
        agenda.has_event(event_id)
        and not agenda.events[event_id].user_created
        and not agenda.event_states[event_id].viewed
    )


# The numbers shown in more than one place (apps.kit.counts): the sidebar on every view.
SHOWN_COUNTS = (
    ShownCount("tasks", untimed(agenda_state.task_count), ("Tasks {n}",)),
    ShownCount(
        "new invitations",
        lambda agenda, now: len(agenda_state.new_invitations(agenda)),
        ("New invitations {n}",),
    ),
)


IMPLICIT_ACTIONS = (
    # Opening an event's details marks it viewed (upstream had a /view endpoint its page
    # never called, §6; the original's "open each event" eval_sql reads isViewed).
    opening("calendar", "event", "view_event", "event_id", applies=unviewed_invitation),
)


MICROLENDAR = declare(__name__, title="MicroLendar", initial_state=empty_agenda)
