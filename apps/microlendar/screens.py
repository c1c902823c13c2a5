"""What each calendar screen shows for a URL: pure functions of (agenda, query, today),
memoised per state (apps.kit.derived.per_state: the fold hands out the same agenda until an
event changes it, so a reload or a live push of an unchanged calendar costs a lookup).

`today` is an input, not read here: it moves with the simulated clock (views.calendar_moment).
The current-time line is not part of a screen (it moves every minute); the template places it.
"""

from __future__ import annotations

import calendar as month_math
from dataclasses import dataclass, replace
from datetime import date, datetime, timedelta
from itertools import groupby

from apps.kit.derived import per_state
from apps.microlendar import times
from apps.microlendar.query import CalendarQuery
from apps.microlendar.state import (
    Agenda,
    CalendarEvent,
    chronological,
    conflicts_with,
    days,
    events_between,
    live_events,
    live_tasks,
    matches_search,
    new_invitations,
)

HOUR_PX = 48  # height of an hour row in the day, week and 4-day grids
MONTH_CHIPS = 3  # events shown in a month cell before "+N more"
GRID_DAYS = {"day": 1, "4days": 4, "week": 7}


@dataclass(frozen=True)
class Chip:
    """An event in a month cell, the schedule or search results: what its link shows."""

    event: CalendarEvent
    url: str
    when: str  # "9:30am" or "9:30 – 10am"
    conflict: bool = False


@dataclass(frozen=True)
class Block:
    """An event placed in a time grid: position in pixels, horizontal share in percent."""

    chip: Chip
    top: int
    height: int
    left: float
    width: float


@dataclass(frozen=True)
class Cell:
    day: date
    url: str  # the day view of this date
    in_month: bool
    is_today: bool
    chips: tuple[Chip, ...]
    more: int


@dataclass(frozen=True)
class Column:
    day: date
    url: str
    is_today: bool
    blocks: tuple[Block, ...]


@dataclass(frozen=True)
class MiniMonth:
    title: str
    url: str
    weeks: tuple[tuple[Cell, ...], ...]
    count: int  # events in the month (year view)


@dataclass(frozen=True)
class Screen:
    view: str
    title: str
    previous_url: str
    next_url: str
    today_url: str
    count: int  # events on shown calendars in the visible range (the header badge)
    weeks: tuple[tuple[Cell, ...], ...] = ()  # month
    columns: tuple[Column, ...] = ()  # day, 4 days, week
    agenda: tuple[tuple[date, tuple[Chip, ...]], ...] = ()  # schedule, search results
    months: tuple[MiniMonth, ...] = ()  # year


# --- periods ------------------------------------------------------------------------------------


def week_start(day: date) -> date:
    """The Sunday on or before `day` (Google Calendar's default first day of the week)."""
    return day - timedelta(days=(day.weekday() + 1) % 7)


def add_months(day: date, months: int) -> date:
    index = day.year * 12 + day.month - 1 + months
    year, month = divmod(index, 12)
    return date(year, month + 1, min(day.day, month_math.monthrange(year, month + 1)[1]))


def month_bounds(day: date) -> tuple[date, date]:
    first = day.replace(day=1)
    return first, first.replace(day=month_math.monthrange(day.year, day.month)[1])


def visible_range(view: str, shown: date) -> tuple[date, date]:
    if view in GRID_DAYS:  # a week from its Sunday, a day and 4 days from the shown date
        first = week_start(shown) if view == "week" else shown
        return first, first + timedelta(days=GRID_DAYS[view] - 1)
    if view == "year":
        return date(shown.year, 1, 1), date(shown.year, 12, 31)
    return month_bounds(shown)  # month, schedule


def step(view: str, shown: date, direction: int) -> date:
    """The date the prev (-1) / next (+1) chevron goes to."""
    if view in GRID_DAYS:
        return shown + timedelta(days=GRID_DAYS[view] * direction)
    if view == "year":
        return add_months(shown, 12 * direction)
    return add_months(shown, direction)


def period_title(view: str, first: date, last: date) -> str:
    """ "September 2025", "Sep – Oct 2025", "Thursday, September 18, 2025", "2025"."""
    if view == "day":
        return f"{first:%A, %B} {first.day}, {first.year}"
    if view == "year":
        return str(first.year)
    if view in ("week", "4days") and first.month != last.month:
        if first.year != last.year:
            return f"{first:%b %Y} – {last:%b %Y}"
        return f"{first:%b} – {last:%b %Y}"
    return f"{first:%B %Y}"


def now_line_top(moment: datetime) -> int:
    """Pixels from the top of a day column to the current-time line."""
    return (moment.hour * 60 + moment.minute) * HOUR_PX // 60


# --- rows ---------------------------------------------------------------------------------------


def chip(agenda: Agenda, query: CalendarQuery, event: CalendarEvent, *, span: bool) -> Chip:
    return Chip(
        event=event,
        url=query.with_item("event", event.id),
        when=times.span(event.start, event.end) if span else times.label(event.start),
        conflict=bool(conflicts_with(agenda, event)),
    )


def place(chips: list[Chip]) -> tuple[Block, ...]:
    """Time-grid layout: events that overlap share the width side by side (each cluster of
    overlapping events gets as many columns as it needs; each event the first free column)."""
    blocks: list[Block] = []
    cluster: list[tuple[Chip, int]] = []
    cluster_end = -1
    ends: list[int] = []  # per column, the end of its last event

    def flush() -> None:
        width = 100.0 / max(len(ends), 1)
        for item, column in cluster:
            e = item.event
            blocks.append(
                Block(
                    chip=item,
                    top=e.start * HOUR_PX // 60,
                    height=max(e.duration * HOUR_PX // 60, HOUR_PX // 3),
                    left=round(column * width, 3),
                    width=round(width, 3),
                )
            )

    for item in sorted(chips, key=lambda c: (c.event.start, -c.event.end, c.event.order)):
        e = item.event
        if cluster and e.start >= cluster_end:
            flush()
            cluster, ends = [], []
        column = next((i for i, end in enumerate(ends) if end <= e.start), None)
        if column is None:
            column = len(ends)
            ends.append(e.end)
        else:
            ends[column] = e.end
        cluster.append((item, column))
        cluster_end = max(cluster_end, e.end)
    if cluster:
        flush()
    return tuple(blocks)


def shown_events(agenda: Agenda, query: CalendarQuery, first: date, last: date):
    hidden = query.hidden
    return [e for e in events_between(agenda, first, last) if e.calendar not in hidden]


def month_weeks(
    agenda: Agenda, query: CalendarQuery, shown: date, today: date, *, mini: bool
) -> tuple[tuple[Cell, ...], ...]:
    """Six weeks from the Sunday before the 1st. In the month view each cell links to its day
    view and shows its first events and "+N more"; in a mini month it moves the screen there."""
    grid = days(week_start(shown.replace(day=1)), 42)
    events = () if mini else shown_events(agenda, query, grid[0], grid[-1])  # in time order
    by_day = {day: list(on_day) for day, on_day in groupby(events, key=lambda e: e.day)}
    cells = []
    for day in grid:
        on_day = by_day.get(day, [])
        cells.append(
            Cell(
                day=day,
                url=query.on(day, today, view=None if mini else "day").querystring(),
                in_month=day.month == shown.month,
                is_today=day == today,
                chips=tuple(chip(agenda, query, e, span=False) for e in on_day[:MONTH_CHIPS]),
                more=max(len(on_day) - MONTH_CHIPS, 0),
            )
        )
    return tuple(tuple(cells[i : i + 7]) for i in range(0, 42, 7))


@per_state()
def mini_month(agenda: Agenda, query: CalendarQuery, shown: date, today: date) -> MiniMonth:
    """The small month of the sidebar (and of the year view)."""
    first, last = month_bounds(shown)
    return MiniMonth(
        title=f"{shown:%B %Y}",
        url=query.on(first, today, view="month").querystring(),
        weeks=month_weeks(agenda, query, shown, today, mini=True),
        count=len(shown_events(agenda, query, first, last)),
    )


@per_state()
def calendar_screen(agenda: Agenda, query: CalendarQuery, today: date) -> Screen:
    view = query.view
    shown = query.shown_date(today)
    first, last = visible_range(view, shown)
    events = shown_events(agenda, query, first, last)
    screen = Screen(
        view=view,
        title=period_title(view, first, last),
        previous_url=query.on(step(view, shown, -1), today).querystring(),
        next_url=query.on(step(view, shown, 1), today).querystring(),
        today_url=query.on(today, today).querystring() or "?",
        count=len(events),
    )
    if query.q:
        found = [e for e in chronological(live_events(agenda)) if matches_search(e, query.q)]
        return replace(screen, agenda=grouped(agenda, query, found))
    if view == "month":
        return replace(screen, weeks=month_weeks(agenda, query, shown, today, mini=False))
    if view in GRID_DAYS:
        columns = []
        for day in days(first, GRID_DAYS[view]):
            chips = [chip(agenda, query, e, span=True) for e in events if e.day == day]
            url = query.on(day, today, view="day").querystring()
            columns.append(Column(day, url, day == today, place(chips)))
        return replace(screen, columns=tuple(columns))
    if view == "schedule":
        return replace(screen, agenda=grouped(agenda, query, events))
    months = tuple(mini_month(agenda, query, date(shown.year, m, 1), today) for m in range(1, 13))
    return replace(screen, months=months)


def grouped(agenda: Agenda, query: CalendarQuery, events: list[CalendarEvent]):
    by_day: dict[date, list[Chip]] = {}
    for event in events:
        by_day.setdefault(event.day, []).append(chip(agenda, query, event, span=True))
    return tuple((day, tuple(chips)) for day, chips in by_day.items())


# --- the open event and the sidebar -----------------------------------------------------------


@dataclass(frozen=True)
class InvitationRow:
    title: str
    when: str  # "Mon, Oct 13 · 9am – 5pm"
    url: str  # the calendar on the invitation's day, its details open (opening marks it seen)


def invitation_rows(agenda: Agenda, query: CalendarQuery) -> tuple[InvitationRow, ...]:
    """The sidebar's "New invitations": what came in during the run and is not opened yet."""
    return tuple(
        InvitationRow(
            title=event.title,
            when=f"{event.day:%a}, {event.day:%b} {event.day.day} · {event.span}",
            url=query.but(date=event.day.isoformat(), event=event.id).querystring() or "?",
        )
        for event in new_invitations(agenda)
    )


@dataclass(frozen=True)
class TaskRow:
    id: str
    title: str
    due: str  # "Due Sep 19" or ""
    overdue: bool
    completed: bool


@per_state()
def task_rows(agenda: Agenda, today: date) -> tuple[TaskRow, ...]:
    """The task list: open tasks first, then completed ones, each in the order they came."""
    rows = [
        TaskRow(
            id=task.id,
            title=task.title,
            due=f"Due {task.due:%b} {task.due.day}" if task.due else "",
            overdue=bool(task.due and task.due < today and not state.completed),
            completed=state.completed,
        )
        for task, state in live_tasks(agenda)
    ]
    return tuple(sorted(rows, key=lambda r: r.completed))
