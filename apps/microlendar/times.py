"""Calendar dates and times as the catalog, the forms and the evaluation tables write them.

Minutes after midnight are the one internal form of a time of day; these functions read and
write the other forms: ISO timestamps ("2025-09-18T09:30:00Z", the catalog's and the `events`
table's), "HH:MM" (forms and `user_created_events`), and Google Calendar's labels ("9:30am").
"""

from __future__ import annotations

import re
from datetime import date, datetime

DATE = re.compile(r"\d{4}-\d{2}-\d{2}")
CLOCK = re.compile(r"([01]?\d|2[0-3]):([0-5]\d)")


class BadTime(ValueError):
    """A date or time a person typed (or a payload carried) that cannot be read."""


def parse_date(text: str, *, field: str = "date") -> date:
    """ "2025-09-18" → date; BadTime naming `field` otherwise."""
    if not DATE.fullmatch(text or ""):
        raise BadTime(f"{field} {text!r} is not a date like 2025-09-18")
    try:
        return date.fromisoformat(text)
    except ValueError:
        raise BadTime(f"{field} {text!r} is not a calendar date") from None


def parse_clock(text: str, *, field: str = "time") -> int:
    """ "09:30" (or "9:30") → 570 minutes after midnight; BadTime naming `field` otherwise."""
    match = CLOCK.fullmatch((text or "").strip())
    if match is None:
        raise BadTime(f"{field} {text!r} is not a time like 09:30")
    return int(match[1]) * 60 + int(match[2])


def hhmm(minutes: int) -> str:
    """570 → "09:30" (24:00 is written 23:59: an event ends on its own day)."""
    minutes = min(max(minutes, 0), 24 * 60 - 1)
    return f"{minutes // 60:02d}:{minutes % 60:02d}"


def label(minutes: int) -> str:
    """Google Calendar's short time: 540 → "9am", 570 → "9:30am", 780 → "1pm"."""
    hour, minute = divmod(min(max(minutes, 0), 24 * 60 - 1), 60)
    suffix = "am" if hour < 12 else "pm"
    hour = hour % 12 or 12
    return f"{hour}{suffix}" if minute == 0 else f"{hour}:{minute:02d}{suffix}"


def hour_label(hour: int) -> str:
    """The hour rows of the time grid: "1 AM" … "11 PM" (no label for midnight)."""
    if hour == 0:
        return ""
    return f"{hour % 12 or 12} {'AM' if hour < 12 else 'PM'}"


def span(start: int, end: int) -> str:
    """ "9:30 – 10:15am", "11am – 1pm" (the meridiem once when both halves share it)."""
    first, last = label(start), label(end)
    if (start < 12 * 60) == (end < 12 * 60):
        first = first[:-2]
    return f"{first} – {last}"


def parse_iso(text: str) -> tuple[date, int]:
    """ "2025-09-18T09:30:00Z" → (date, 570); the zone is ignored (calendar time)."""
    moment = datetime.fromisoformat(str(text).replace("Z", "+00:00"))
    return moment.date(), moment.hour * 60 + moment.minute


def iso(day: date, minutes: int) -> str:
    """(date, 570) → "2025-09-18T09:30:00Z", the catalog's and the `events` table's form."""
    return f"{day.isoformat()}T{hhmm(minutes)}:00Z"
