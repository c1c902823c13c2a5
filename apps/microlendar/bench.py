"""The MicroLendar pages worth timing (`manage.py bench_pages --env microlendar`), relative to
the environment root (`/r/<token>/microlendar/`)."""

from __future__ import annotations

from apps.microlendar.query import VIEWS, CalendarQuery
from apps.microlendar.state import Agenda, chronological, live_events


def sample_pages(agenda: Agenda) -> list[str]:
    pages = [CalendarQuery(view=view).querystring() or "?" for view in VIEWS]
    pages += ["events/new", CalendarQuery(q="review").querystring()]
    events = chronological(live_events(agenda))
    if events:
        first = events[len(events) // 2]
        day = first.day.isoformat()
        pages += [
            CalendarQuery(view="week", date=day).querystring(),
            CalendarQuery(view="month", date=day).with_item("event", first.id),
            f"events/{first.id}/edit",
        ]
    return pages
