"""The calendar URL: view, shown date, search, hidden calendars and open event.

`/r/<token>/microlendar/?view=week&date=2025-09-18&q=hawaii&off=Family&event=<id>` — every
screen is a stable, shareable URL, canonical (defaults left out). Without `date` the calendar
shows the simulated today. Upstream kept the view in the hash (`#week`) and the date nowhere.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from datetime import date
from typing import Self

from apps.kit.query import InvalidQuery, QueryState, choice, item, text
from apps.microlendar import times
from apps.microlendar.state import CALENDARS

VIEWS: tuple[str, ...] = ("day", "week", "month", "year", "schedule", "4days")
VIEW_TITLES: Mapping[str, str] = {view: view.title() for view in VIEWS} | {"4days": "4 days"}


@dataclass(frozen=True)
class CalendarQuery(QueryState):
    view: str = choice(VIEWS, default="month", not_found=True)
    date: str = text(max_length=10)
    q: str = text()
    off: str = text(max_length=60)  # hidden calendars, comma separated (display only)
    event: str | None = item()

    @classmethod
    def from_params(cls, params: Mapping[str, str]) -> Self:
        query = super().from_params(params)
        if query.date:
            try:
                times.parse_date(query.date)
            except times.BadTime as exc:
                raise InvalidQuery(f"{exc}; e.g. date=2025-09-18") from None
        unknown = [name for name in query.off.split(",") if name and name not in CALENDARS]
        if unknown:
            raise InvalidQuery(
                f"off={unknown[0]!r} is not a calendar; allowed: {', '.join(CALENDARS)}"
            )
        return query

    def shown_date(self, today: date) -> date:
        """The date the screen is about: `date`, else today."""
        return times.parse_date(self.date) if self.date else today

    @property
    def hidden(self) -> frozenset[str]:
        return frozenset(name for name in self.off.split(",") if name)

    def toggling(self, calendar: str) -> str:
        """This screen with `calendar` shown if hidden, hidden if shown."""
        hidden = set(self.hidden) ^ {calendar}
        return self.but(off=",".join(c for c in CALENDARS if c in hidden), event=None).querystring()

    def on(self, day: date, today: date, view: str | None = None) -> Self:
        """This screen moved to `day` (the date left out when it is today), optionally another
        view; an open event is closed."""
        return self.but(
            date="" if day == today else day.isoformat(), view=view or self.view, event=None
        )
