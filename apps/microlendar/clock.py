"""The calendar's own clock: the preload's day, moving with the run's simulated time.

Simulated second 0 is 09:00 (apps.kit.simclock) on the day the scenario opens the
calendar on (`initial_date`, else `today`, else the run's day zero), so "today" and the red
current-time line move on the simulated clock exactly as the shell's time does, and a run that
goes past midnight turns the page to the next day.
"""

from __future__ import annotations

from datetime import datetime

from apps.kit import simclock
from apps.microlendar.screens import HOUR_PX
from apps.microlendar.state import Agenda


def calendar_moment(agenda: Agenda, page) -> datetime:
    """The page's simulated moment on the calendar; the page is pushed again next minute."""
    page.changes_at(simclock.next_minute(page.now))
    start = agenda.initial_date or agenda.today or simclock.day_zero(page.run)
    return simclock.moment(page.now, start)


def now_line_top(moment: datetime) -> int:
    """Pixels from the top of a day column to the current-time line."""
    return (moment.hour * 60 + moment.minute) * HOUR_PX // 60
