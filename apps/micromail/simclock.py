"""Moved to `apps.agent_site.simclock` (shared by every environment); kept for old imports."""

from apps.agent_site.simclock import DAY_S, DAY_START_S, ago, clock_time  # noqa: F401
