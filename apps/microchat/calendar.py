"""The calendar tab's grid: a day, a work week or a month around today, with the meetings of
the workspace's meeting chats (those the catalog schedules) in their slots."""

from __future__ import annotations

import calendar as stdlib_calendar
from collections.abc import Iterable
from dataclasses import dataclass
from datetime import date, timedelta

from apps.microchat.query import CalendarQuery

FIRST_HOUR, LAST_HOUR = 8, 18  # the hours a day or week grid shows
WORK_WEEK = 5


def working_day(start: date, n: int) -> date:
    """The `n`-th working day (Monday to Friday) counting from `start`, back from it if `n` is
    negative: day 0 is `start` itself if it is one, else the Monday after. A catalog schedules
    work meetings this way so that a run started on any weekday never puts one on a weekend."""
    day = start
    while day.weekday() >= WORK_WEEK:
        day += timedelta(days=1)
    step = timedelta(days=1 if n >= 0 else -1)
    for _ in range(abs(n)):
        day += step
        while day.weekday() >= WORK_WEEK:
            day += step
    return day


@dataclass(frozen=True)
class Day:
    day: date
    is_today: bool
    in_month: bool
    meetings: tuple  # screens.Meeting


@dataclass(frozen=True)
class Grid:
    view: str
    title: str
    days: tuple[Day, ...]
    weeks: tuple[tuple[Day, ...], ...]  # month view only
    hours: tuple[str, ...]
    prev_url: str
    next_url: str
    today_url: str


def _days(start: date, count: int, today: date, month: int, meetings: Iterable) -> tuple[Day, ...]:
    by_day: dict[date, list] = {}
    for meeting in meetings:
        by_day.setdefault(meeting.day, []).append(meeting)
    return tuple(
        Day(d, d == today, d.month == month, tuple(by_day.get(d, ())))
        for d in (start + timedelta(days=n) for n in range(count))
    )


def _shifted(today: date, view: str, offset: int) -> date:
    if view == "day":
        return today + timedelta(days=offset)
    if view == "week":
        return today + timedelta(weeks=offset)
    month_index = today.year * 12 + today.month - 1 + offset
    return date(month_index // 12, month_index % 12 + 1, 1)


def calendar_grid(query: CalendarQuery, today: date, meetings: tuple) -> Grid:
    offset = int(query.offset)
    anchor = _shifted(today, query.view, offset)
    weeks: tuple[tuple[Day, ...], ...] = ()
    if query.view == "day":
        days = _days(anchor, 1, today, anchor.month, meetings)
        title = f"{anchor:%A} {anchor.day} {anchor:%B %Y}"
    elif query.view == "week":
        # On a Saturday or Sunday the work week shown is the coming one, where the catalog puts
        # the meetings of a run started at a weekend (working_day's day 0).
        first = working_day(anchor, 0)
        monday = first - timedelta(days=first.weekday())
        days = _days(monday, WORK_WEEK, today, anchor.month, meetings)
        friday = monday + timedelta(days=WORK_WEEK - 1)
        title = f"{monday.day} {monday:%b} – {friday.day} {friday:%b %Y}"
    else:
        first_weekday, length = stdlib_calendar.monthrange(anchor.year, anchor.month)
        start = anchor - timedelta(days=first_weekday)
        count = ((first_weekday + length + 6) // 7) * 7
        days = _days(start, count, today, anchor.month, meetings)
        weeks = tuple(days[n : n + 7] for n in range(0, count, 7))
        title = f"{anchor:%B %Y}"

    def at(n: int) -> str:
        return query.but(offset=str(max(-8, min(8, n)))).querystring()

    return Grid(
        view=query.view,
        title=title,
        days=days,
        weeks=weeks,
        hours=tuple(f"{h:02d}:00" for h in range(FIRST_HOUR, LAST_HOUR)),
        prev_url="calendar" + at(offset - 1),
        next_url="calendar" + at(offset + 1),
        today_url="calendar" + query.but(offset="0").querystring(),
    )
