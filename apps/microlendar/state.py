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
from dataclasses import dataclass
from datetime import date, timedelta
from types import MappingProxyType
from typing import Any, ClassVar

from apps.kit.records import flag, from_catalog, integer, text_or
from apps.kit.retractions import is_gone, still_there
from apps.kit.state import SelfUserState, with_items
from apps.kit.streaming import no_items
from apps.microlendar import times

ENVIRONMENT = "microlendar"

CALENDARS: tuple[str, ...] = ("Work", "Family", "Personal", "Tasks")
DEFAULT_CALENDAR = "Work"
# Google Calendar's palette, as upstream coloured its calendars.
CALENDAR_COLORS: Mapping[str, str] = MappingProxyType(
    {"Work": "#039BE5", "Family": "#33B679", "Personal": "#7986CB", "Tasks": "#F4511E"}
)
DEFAULT_DURATION_MIN = 60  # an event without an end lasts an hour (upstream's conflict rule)
DAY_MIN = 24 * 60


@dataclass(frozen=True)
class Attendee:
    id: str
    name: str
    email: str = from_catalog(text_or("email"), default="")
    job_title: str = from_catalog(text_or("jobTitle"), default="")


@dataclass(frozen=True)
class CalendarEvent:
    """One event as it stands now (edits replace the value; the id never changes)."""

    id: str
    title: str = from_catalog(text_or("title", "(No title)"))
    day: date
    start: int  # minutes after midnight
    end: int  # minutes after midnight, > start (an event ends on the day it starts)
    calendar: str = DEFAULT_CALENDAR
    description: str = from_catalog(text_or("description"), default="")
    location: str = from_catalog(text_or("location"), default="")
    attendees: tuple[Attendee, ...] = ()
    # Who invited the user (the catalog's `organizer`); None: the user organises it themselves.
    organizer: Attendee | None = None
    user_created: bool = False
    # the catalog's display order, for events starting at the same minute
    order: int = from_catalog(integer("order"), default=0)
    arrived_at: float = 0.0  # simulated second it reached the calendar (0: the starting world)
    gone_at: float | None = None  # cancelled by its organiser then (apps.kit.retractions)

    @property
    def color(self) -> str:
        return CALENDAR_COLORS.get(self.calendar, CALENDAR_COLORS[DEFAULT_CALENDAR])

    @property
    def span(self) -> str:
        """ "9:30 – 10:15am", as the event's details show its times."""
        return times.span(self.start, self.end)

    @property
    def duration(self) -> int:
        return self.end - self.start

    def overlaps(self, other: CalendarEvent) -> bool:
        """Same day and [start, end) minute ranges intersect (upstream's conflict rule)."""
        return self.day == other.day and self.start < other.end and other.start < self.end


@dataclass(frozen=True)
class Guest:
    """A row of an event's guest list: who, and what Google shows under the name."""

    person: Attendee
    note: str  # "Organizer", the user's answer to an invitation, or the job title


@dataclass(frozen=True)
class EventState:
    viewed: bool = False  # opened in the event details (upstream `isViewed`)
    deleted: bool = False
    # Delivered while the user was away from the calendar's start, i.e. an invitation that came
    # in during the run: until opened, the sidebar lists it as a new invitation.
    arrived_during_run: bool = False


@dataclass(frozen=True)
class Task:
    id: str
    title: str = from_catalog(text_or("title", "(No title)"))
    due: date | None = None
    user_created: bool = False


@dataclass(frozen=True)
class TaskState:
    completed: bool = from_catalog(flag("is_completed"), default=False)
    deleted: bool = False


@dataclass(frozen=True)
class Agenda(SelfUserState):
    FALLBACK: ClassVar[Mapping[str, str]] = MappingProxyType(
        {"id": "self", "name": "Me", "email": "me@microlendar.local"}
    )
    today: date | None = None  # the preload's `today`: what "today" means for the baselines
    initial_date: date | None = None  # the preload's `initial_date`: the day the UI opens on
    events: Mapping[str, CalendarEvent] = no_items()  # load order
    event_states: Mapping[str, EventState] = no_items()
    tasks: Mapping[str, Task] = no_items()
    task_states: Mapping[str, TaskState] = no_items()

    def has_event(self, event_id: str) -> bool:
        """Delivered, not deleted and not cancelled: what the calendar shows."""
        state = self.event_states.get(event_id)
        return state is not None and not state.deleted and still_there(self.events, event_id)

    def cancelled(self, event_id: str) -> bool:
        """Delivered, then cancelled by its organiser: gone from the calendar, and its details,
        if open, say so."""
        event = self.events.get(event_id)
        return event is not None and is_gone(event)

    def response(self, event_id: str) -> str:
        """The user's answer to an invitation. There is no reply button: one already on the
        calendar when the run starts was accepted; one that came in during the run awaits it."""
        state = self.event_states.get(event_id)
        return "Awaiting response" if state and state.arrived_during_run else "Accepted"

    def has_task(self, task_id: str) -> bool:
        state = self.task_states.get(task_id)
        return state is not None and not state.deleted

    def created_count(self, kind: str) -> int:
        """How many `kind`s ("event", "task") the user created, deleted ones included (they are
        only marked deleted): the number in the next one's id."""
        return sum(1 for item in getattr(self, f"{kind}s").values() if item.user_created)


empty_agenda = Agenda.of


# --- building new states (used by reducers only) --------------------------------------------


def with_created(agenda: Agenda, kind: str, item: CalendarEvent | Task, state: Any) -> Agenda:
    """Add what the user created (`kind` "event" or "task") with its state. An id already there
    is the same creation replayed: the agenda is left as it is."""
    if item.id in getattr(agenda, f"{kind}s"):
        return agenda
    agenda = with_items(agenda, f"{kind}s", [(item.id, item)])
    return with_items(agenda, f"{kind}_states", [(item.id, state)])


# --- what the calendar holds ---------------------------------------------------------------------


def live_events(agenda: Agenda) -> list[CalendarEvent]:
    """Every event not deleted nor cancelled, in delivery order."""
    return [e for e in agenda.events.values() if agenda.has_event(e.id)]


def guests(agenda: Agenda, event: CalendarEvent) -> tuple[Guest, ...]:
    """The guest list as Google Calendar's event details give it: the organiser first, then the
    user (with their answer, when someone else invited them), then the other attendees."""
    me = Attendee(id=agenda.self_id, name=agenda.self_name, email=agenda.self_email)
    if event.organizer is None:
        first = (Guest(me, "Organizer"),)
    else:
        first = (Guest(event.organizer, "Organizer"), Guest(me, agenda.response(event.id)))
    listed = {guest.person.id for guest in first}
    others = (Guest(p, p.job_title) for p in event.attendees if p.id not in listed)
    return (*first, *others)


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


def task_count(agenda: Agenda) -> int:
    return len(live_tasks(agenda))


def conflict_count(agenda: Agenda) -> int:
    """Pairs of events on the same day whose times overlap (each pair has two ends)."""
    return sum(len(conflicts_with(agenda, event)) for event in live_events(agenda)) // 2


def new_invitations(agenda: Agenda) -> list[CalendarEvent]:
    """Invitations that came in during the run and were not opened yet, newest first: the
    notice a calendar shows for an invitation arriving on a day the user is not looking at."""
    return [
        event
        for event in reversed(live_events(agenda))
        if not event.user_created
        and agenda.event_states[event.id].arrived_during_run
        and not agenda.event_states[event.id].viewed
    ]


def days(first: date, count: int) -> list[date]:
    return [first + timedelta(days=n) for n in range(count)]
