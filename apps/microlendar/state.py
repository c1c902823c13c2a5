"""The calendar as immutable values, and the questions pages and baselines ask of it.

`Agenda` is what the reducers build and what every page, baseline and evaluation reads. It is
never mutated: a reducer returns a new `Agenda`. Events delivered from the catalog and events
the user created live side by side (`CalendarEvent.user_created`), because upstream keeps them
in separate evaluation tables (`events` / `user_created_events`); tasks likewise.

Times are wall-calendar times without a zone: "2025-09-18T09:00:00Z" in the catalog is 09:00 on
the calendar, whatever zone the browser is in (upstream shifted days outside UTC, §6).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from datetime import date, timedelta
from types import MappingProxyType
from typing import Any

from apps.kit.frozen import with_changed, with_items

ENVIRONMENT = "microlendar"

CALENDARS: tuple[str, ...] = ("Work", "Family", "Personal", "Tasks")
DEFAULT_CALENDAR = "Work"
# Google Calendar's palette, as upstream coloured its calendars.
CALENDAR_COLORS: Mapping[str, str] = MappingProxyType(
    {"Work": "#039BE5", "Family": "#33B679", "Personal": "#7986CB", "Tasks": "#F4511E"}
)
DEFAULT_DURATION_MIN = 60  # an event without an end lasts an hour (upstream's conflict rule)
DAY_MIN = 24 * 60

FALLBACK_SELF: Mapping[str, Any] = MappingProxyType(
    {"id": "self", "name": "Me", "email": "me@microlendar.local"}
)
EMPTY: Mapping = MappingProxyType({})


@dataclass(frozen=True)
class Attendee:
    id: str
    name: str
    email: str = ""
    job_title: str = ""


@dataclass(frozen=True)
class CalendarEvent:
    """One event as it stands now (edits replace the value; the id never changes)."""

    id: str
    title: str
    day: date
    start: int  # minutes after midnight
    end: int  # minutes after midnight, > start (an event ends on the day it starts)
    calendar: str = DEFAULT_CALENDAR
    description: str = ""
    location: str = ""
    attendees: tuple[Attendee, ...] = ()
    user_created: bool = False
    order: int = 0  # the catalog's display order, for events starting at the same minute

    @property
    def color(self) -> str:
        return CALENDAR_COLORS.get(self.calendar, CALENDAR_COLORS[DEFAULT_CALENDAR])

    @property
    def duration(self) -> int:
        return self.end - self.start

    def overlaps(self, other: CalendarEvent) -> bool:
        """Same day and [start, end) minute ranges intersect (upstream's conflict rule)."""
        return self.day == other.day and self.start < other.end and other.start < self.end


@dataclass(frozen=True)
class EventState:
    viewed: bool = False  # opened in the event details (upstream `isViewed`)
    deleted: bool = False


@dataclass(frozen=True)
class Task:
    id: str
    title: str
    due: date | None = None
    notes: str = ""
    user_created: bool = False


@dataclass(frozen=True)
class TaskState:
    completed: bool = False
    deleted: bool = False


@dataclass(frozen=True)
class Agenda:
    # The catalog and self user are inputs, not state: excluded from equality so that two folds
    # of the same log compare equal cheaply.
    catalog: Any = field(compare=False, repr=False)
    self_user: Mapping[str, Any] = field(
        compare=False, repr=False, default_factory=lambda: FALLBACK_SELF
    )
    today: date | None = None  # the preload's `today`: what "today" means for the baselines
    initial_date: date | None = None  # the preload's `initial_date`: the day the UI opens on
    events: Mapping[str, CalendarEvent] = field(default_factory=lambda: EMPTY)  # load order
    event_states: Mapping[str, EventState] = field(default_factory=lambda: EMPTY)
    tasks: Mapping[str, Task] = field(default_factory=lambda: EMPTY)
    task_states: Mapping[str, TaskState] = field(default_factory=lambda: EMPTY)

    @property
    def self_name(self) -> str:
        return str(self.self_user.get("name") or FALLBACK_SELF["name"])

    @property
    def self_email(self) -> str:
        return str(self.self_user.get("email") or FALLBACK_SELF["email"])

    def has_event(self, event_id: str) -> bool:
        """Delivered and not deleted: what the calendar shows."""
        state = self.event_states.get(event_id)
        return state is not None and not state.deleted

    def has_task(self, task_id: str) -> bool:
        state = self.task_states.get(task_id)
        return state is not None and not state.deleted

    def user_event_count(self) -> int:
        """User-created events so far, deleted ones included (they are only marked deleted)."""
        return sum(1 for e in self.events.values() if e.user_created)

    def user_task_count(self) -> int:
        return sum(1 for t in self.tasks.values() if t.user_created)


def empty_agenda(catalog: Any) -> Agenda:
    return Agenda(catalog=catalog, self_user=getattr(catalog, "self_user", None) or FALLBACK_SELF)


# --- building new states (used by reducers only) --------------------------------------------


def with_events(agenda: Agenda, arrivals: Iterable[CalendarEvent]) -> Agenda:
    """Add events, each with a fresh state (not viewed, not deleted)."""
    arrivals = list(arrivals)
    agenda = with_items(agenda, "events", [(event.id, event) for event in arrivals])
    return with_items(agenda, "event_states", [(event.id, EventState()) for event in arrivals])


def with_event(agenda: Agenda, event_id: str, **changes: Any) -> Agenda:
    """Edit an event's fields; an id that is gone leaves the calendar as it is."""
    return with_changed(agenda, "events", event_id, **changes)


def with_event_state(agenda: Agenda, event_id: str, **changes: Any) -> Agenda:
    return with_changed(agenda, "event_states", event_id, **changes)


def with_tasks(agenda: Agenda, arrivals: Iterable[tuple[Task, TaskState]]) -> Agenda:
    arrivals = list(arrivals)
    agenda = with_items(agenda, "tasks", [(task.id, task) for task, _ in arrivals])
    return with_items(agenda, "task_states", [(task.id, state) for task, state in arrivals])


def with_task_state(agenda: Agenda, task_id: str, **changes: Any) -> Agenda:
    return with_changed(agenda, "task_states", task_id, **changes)


# --- what the calendar holds ---------------------------------------------------------------------


def live_events(agenda: Agenda) -> list[CalendarEvent]:
    """Every event not deleted, in delivery order."""
    return [e for e in agenda.events.values() if not agenda.event_states[e.id].deleted]


def live_tasks(agenda: Agenda) -> list[tuple[Task, TaskState]]:
    return [(t, agenda.task_states[t.id]) for t in agenda.tasks.values() if agenda.has_task(t.id)]


def chronological(events: Iterable[CalendarEvent]) -> list[CalendarEvent]:
    return sorted(events, key=lambda e: (e.day, e.start, e.end, e.order, e.id))


def events_between(agenda: Agenda, first: date, last: date) -> list[CalendarEvent]:
    """Events from `first` to `last` inclusive, in time order."""
    return chronological(e for e in live_events(agenda) if first <= e.day <= last)


def matches_search(event: CalendarEvent, query: str) -> bool:
    """Case-insensitive substring over title, description and location (upstream's search)."""
    needle = query.strip().casefold()
    return bool(needle) and any(
        needle in text.casefold() for text in (event.title, event.description, event.location)
    )


def conflicts_with(agenda: Agenda, event: CalendarEvent) -> list[CalendarEvent]:
    """Other events of the same day that overlap `event`."""
    return [
        other for other in live_events(agenda) if other.id != event.id and other.overlaps(event)
    ]


# --- counts (baselines and badges) ---------------------------------------------------------------
# Upstream counted user-created events in event_count only (they lacked start_time and category);
# here they count everywhere, as the calendar shows them. Baselines are measured right after the
# preload, when no user event exists yet, so the original scenarios see the same numbers.


def event_count(agenda: Agenda) -> int:
    return len(live_events(agenda))


def today_event_count(agenda: Agenda) -> int:
    return sum(1 for e in live_events(agenda) if e.day == agenda.today)


def calendar_event_count(agenda: Agenda, calendar: str) -> int:
    return sum(1 for e in live_events(agenda) if e.calendar == calendar)


def work_event_count(agenda: Agenda) -> int:
    return calendar_event_count(agenda, "Work")


def personal_event_count(agenda: Agenda) -> int:
    return calendar_event_count(agenda, "Personal")


def task_count(agenda: Agenda) -> int:
    return len(live_tasks(agenda))


def conflict_count(agenda: Agenda) -> int:
    """Pairs of events on the same day whose times overlap."""
    by_day: dict[date, list[CalendarEvent]] = {}
    for event in live_events(agenda):
        by_day.setdefault(event.day, []).append(event)
    return sum(
        1
        for day_events in by_day.values()
        for i, first in enumerate(day_events)
        for second in day_events[i + 1 :]
        if first.overlaps(second)
    )


def days(first: date, count: int) -> list[date]:
    return [first + timedelta(days=n) for n in range(count)]
