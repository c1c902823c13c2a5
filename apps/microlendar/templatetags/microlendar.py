"""Template tags for MicroLendar pages: the hour labels of the time grid, times as Google writes
them. (Event chips and time-grid blocks are the kit's `{% rows %}`.)"""

from __future__ import annotations

from django import template

from apps.microlendar import times

register = template.Library()

HOURS = tuple((hour, times.hour_label(hour)) for hour in range(24))


@register.simple_tag
def hour_rows() -> tuple[tuple[int, str], ...]:
    return HOURS


register.filter("clock_label", times.label)
register.filter("hhmm", times.hhmm)
