"""Simulated time as pages show it, from the run's clock — never the browser's.

Every environment renders times with these helpers (template filters in
`apps/kit/templatetags/simtime.py`), so acceleration and a virtual clock look the same to
every client and to the replay viewer.

The simulated workday starts at 09:00: simulated second 0 is 09:00 on the run's *day zero*, the
UTC date the run was created (stored on the run, so a replay shows the same dates). A message
preloaded "five minutes before start" reads 08:55. Apart from `day_zero`, these are pure
functions of floats and dates.
"""

from __future__ import annotations

from datetime import date, datetime, time, timedelta

DAY_START_S = 9 * 3600  # sim second 0 is 09:00
DAY_S = 24 * 3600


def day_zero(run) -> date:
    """The calendar date of simulated second 0 for `run` (its creation date, UTC)."""
    created = getattr(run, "created_at", None)
    return created.date() if created is not None else date(2025, 1, 6)


def moment(at: float, zero: date) -> datetime:
    """Simulated second `at` as a (naive) date and time on the simulated calendar."""
    return datetime.combine(zero, time()) + timedelta(seconds=DAY_START_S + at)


def clock_time(at: float) -> str:
    """`at` (simulated seconds) as hh:mm on the simulated day."""
    seconds = int((DAY_START_S + at) // 60 * 60) % DAY_S
    return f"{seconds // 3600:02d}:{seconds % 3600 // 60:02d}"


def next_minute(now: float) -> float:
    """When the hh:mm of the simulated clock next turns over."""
    return (DAY_START_S + now) // 60 * 60 + 60 - DAY_START_S


def ago_changes_at(at: float, now: float) -> float | None:
    """When `ago(at, now)` next reads differently (None: it has settled on hh:mm for good)."""
    elapsed = max(0.0, now - at)
    if elapsed < 3600:
        return at + (elapsed // 60 + 1) * 60
    return None


def relative_changes_at(at: float, now: float, zero: date) -> float | None:
    """When `relative(at, now, zero)` next reads differently: the next minute within the hour,
    then at each midnight ("Yesterday", then the date)."""
    if now - at < 3600:
        return ago_changes_at(at, now)
    midnight = datetime.combine(moment(now, zero).date() + timedelta(days=1), time())
    then = moment(at, zero).date()
    if then < moment(now, zero).date() - timedelta(days=1):
        return None  # already shown as a date
    return now + (midnight - moment(now, zero)).total_seconds()


def ago(at: float, now: float) -> str:
    """How long before `now` the moment `at` was: "just now", "5 min ago", else hh:mm."""
    elapsed = max(0.0, now - at)
    if elapsed < 60:
        return "just now"
    if elapsed < 3600:
        return f"{int(elapsed // 60)} min ago"
    return clock_time(at)


def relative(at: float, now: float, zero: date) -> str:
    """Like `ago`, and beyond the hour names the day: "14:05", "Yesterday 17:30", "Mon 3 Mar"."""
    elapsed = max(0.0, now - at)
    if elapsed < 3600:
        return ago(at, now)
    then, today = moment(at, zero), moment(now, zero).date()
    if then.date() == today:
        return clock_time(at)
    if then.date() == today - timedelta(days=1):
        return f"Yesterday {clock_time(at)}"
    return f"{then:%a} {then.day} {then:%b}"


# Elapsed-time units, largest first, as social products count them (no months: a week count
# keeps growing, "12w", as they do). A product that counts months passes its own.
UNITS = (("week", 7 * DAY_S), ("day", DAY_S), ("hour", 3600), ("minute", 60))
Units = tuple[tuple[str, int], ...]


def _whole_units(at: float, now: float, units: Units) -> tuple[str, int, int] | None:
    """(unit, its size, how many) of the largest unit that fits in `now - at`; None under a
    minute."""
    # A microsecond of slack: `at + n * size` minus `at` can fall a hair short of `n * size` in
    # floating point, and the text must move at exactly the moment `units_changes_at` names.
    elapsed = max(0.0, now - at) + 1e-6
    for unit, size in units:
        if elapsed >= size:
            return unit, size, int(elapsed // size)
    return None


def units_changes_at(at: float, now: float, units: Units = UNITS) -> float:
    """When `compact_ago` / `long_ago` next read differently: the next whole unit."""
    whole = _whole_units(at, now, units)
    size, count = (whole[1], whole[2]) if whole else (60, 0)
    return at + (count + 1) * size


def compact_ago(at: float, now: float) -> str:
    """How long ago, as feeds write it: "now", "5m", "2h", "3d", "1w"."""
    whole = _whole_units(at, now, UNITS)
    return f"{whole[2]}{whole[0][0]}" if whole else "now"


def long_ago(at: float, now: float, units: Units = UNITS, *, just_now: str = "just now") -> str:
    """How long ago, in words: "just now", "1 minute ago", "3 hours ago", "2 weeks ago"."""
    whole = _whole_units(at, now, units)
    if whole is None:
        return just_now
    unit, _, count = whole
    return f"{count} {unit}{'' if count == 1 else 's'} ago"


def absolute(at: float, zero: date) -> str:
    """The full simulated date and time: "Mon 6 Jan 2025, 09:12"."""
    then = moment(at, zero)
    return f"{then:%a} {then.day} {then:%b %Y}, {clock_time(at)}"


def today(now: float, zero: date) -> date:
    """The simulated calendar date at simulated second `now`."""
    return moment(now, zero).date()
