"""Template filters for simulated time, shared by every environment.

    {% load simtime %}
    {{ email.arrived_at|sim_ago:page.now }}     just now · 5 min ago · 08:55
    {{ event.at|sim_relative:page }}            … · 14:05 · Yesterday 17:30 · Mon 3 Mar
    {{ event.at|sim_absolute:page }}            Mon 6 Jan 2025, 09:12
    {{ event.at|sim_clock }}                    09:12
    {{ page|sim_today }}                        Monday 6 January 2025
    {{ page|sim_today:"Y-m-d" }}                2025-01-06 (any Django date format)

`page` is the `apps.agent_site.pages.Page` of the request: its `now` was read once from the run's
clock, so every time on a page agrees.
"""

from __future__ import annotations

from django import template
from django.utils.dateformat import format as format_date

from apps.agent_site import simclock

register = template.Library()


@register.filter
def sim_ago(at: float, now: float) -> str:
    return simclock.ago(at, now)


@register.filter
def sim_clock(at: float) -> str:
    return simclock.clock_time(at)


@register.filter
def sim_relative(at: float, page) -> str:
    return simclock.relative(at, page.now, simclock.day_zero(page.run))


@register.filter
def sim_absolute(at: float, page) -> str:
    return simclock.absolute(at, simclock.day_zero(page.run))


@register.filter
def sim_today(page, fmt: str = "l j F Y") -> str:
    return format_date(simclock.today(page.now, simclock.day_zero(page.run)), fmt)
