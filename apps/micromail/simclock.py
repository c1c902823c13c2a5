"""Showing simulated times ("5 min ago", "09:12"), from the run's clock, never the browser's.

The simulated workday starts at 09:00: simulated second 0 is shown as 09:00, so a message
preloaded "five minutes before start" reads 08:55. Pure functions of two floats, so every
client and the replay viewer render the same text for the same moment.
"""

from __future__ import annotations

DAY_START_S = 9 * 3600  # sim second 0 is 09:00
DAY_S = 24 * 3600


def clock_time(at: float) -> str:
    """`at` (simulated seconds) as hh:mm on the simulated day."""
    seconds = int((DAY_START_S + at) // 60 * 60) % DAY_S
    return f"{seconds // 3600:02d}:{seconds % 3600 // 60:02d}"


def ago(at: float, now: float) -> str:
    """How long before `now` the moment `at` was: "just now", "5 min ago", else hh:mm."""
    elapsed = max(0.0, now - at)
    if elapsed < 60:
        return "just now"
    if elapsed < 3600:
        return f"{int(elapsed // 60)} min ago"
    return clock_time(at)
