"""Template filters for simulated time, shared by every environment.

    {% load simtime %}
    {{ email.arrived_at|sim_ago:page }}         just now · 5 min ago · 08:55
    {{ post.at|sim_ago_compact:page }}          now · 5m · 2h · 3d · 1w
    {{ video.at|sim_ago_long:page }}            just now · 1 minute ago · 3 hours ago · 2 weeks ago
    {{ event.at|sim_relative:page }}            … · 14:05 · Yesterday 17:30 · Mon 3 Mar
    {{ event.at|sim_absolute:page }}            Mon 6 Jan 2025, 09:12
    {{ event.at|sim_clock }}                    09:12
    {{ page|sim_today }}                        Monday 6 January 2025
    {{ page|sim_today:"Y-m-d" }}                2025-01-06 (any Django date format)
    {{ page|sim_now|date:"D j M H:i" }}         Mon 6 Jan 09:12 (the page's own moment)

`page` is the `apps.kit.pages.Page` of the request: its `now` was read once from the run's
clock, so every time on a page agrees. Filters whose text moves on with the clock (`sim_ago`,
`sim_ago_compact`, `sim_ago_long`, `sim_relative`, `sim_now`) tell the page when it next changes (`page.changes_at`), so a live
page is pushed again then. `sim_ago` and `sim_relative` also take a plain `now` (simulated
seconds) instead of the page; nothing is registered then.
"""

from __future__ import annotations

from datetime import datetime

from django import template
from django.utils.dateformat import format as format_date

from apps.kit import simclock

register = template.Library()


@register.filter
def sim_ago(at: float, page) -> str:
    if isinstance(page, int | float):
        return simclock.ago(at, page)
    page.ages_at(simclock.ago_changes_at(at, page.now))
    return simclock.ago(at, page.now)


@register.filter
def sim_ago_compact(at: float, page) -> str:
    if isinstance(page, int | float):
        return simclock.compact_ago(at, page)
    page.ages_at(simclock.units_changes_at(at, page.now))
    return simclock.compact_ago(at, page.now)


@register.filter
def sim_ago_long(at: float, page) -> str:
    if isinstance(page, int | float):
        return simclock.long_ago(at, page)
    page.ages_at(simclock.units_changes_at(at, page.now))
    return simclock.long_ago(at, page.now)


@register.filter
def sim_clock(at: float) -> str:
    return simclock.clock_time(at)


@register.filter
def sim_relative(at: float, page) -> str:
    if isinstance(page, int | float):
        return simclock.relative(at, page, simclock.day_zero(None))
    zero = simclock.day_zero(page.run)
    page.ages_at(simclock.relative_changes_at(at, page.now, zero))
    return simclock.relative(at, page.now, zero)


@register.filter
def sim_absolute(at: float, page) -> str:
    return simclock.absolute(at, simclock.day_zero(page.run))


@register.filter
def sim_today(page, fmt: str = "l j F Y") -> str:
    return format_date(simclock.today(page.now, simclock.day_zero(page.run)), fmt)


@register.filter
def sim_now(page) -> datetime:
    """The page's simulated moment as a date and time, for `|date` formats shown to the minute
    (the page is pushed again when the minute turns)."""
    page.changes_at(simclock.next_minute(page.now))
    return simclock.moment(page.now, simclock.day_zero(page.run))
