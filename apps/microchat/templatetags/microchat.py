"""Template filters for MicroChat pages: Teams' dates and times, reactions, light markdown.

Chat-list rows and messages are rendered once per distinct input (the kit's `{% row %}`), so
what they show of the clock goes in as text: `chat_day` and `message_stamp` give it.
"""

from __future__ import annotations

from datetime import datetime

from django import template

from apps.kit import simclock
from apps.kit.templatetags.simtime import sim_relative
from apps.microchat.markup import render_markup
from apps.microchat.state import REACTIONS

register = template.Library()
register.filter("markup", render_markup)


def days_ago(at: float, page) -> tuple[datetime, int]:
    """The moment `at` on the page's calendar, and how many days before today it falls."""
    zero = simclock.day_zero(page.run)
    then = simclock.moment(at, zero)
    return then, (simclock.today(page.now, zero) - then.date()).days


@register.filter
def chat_day(at: float | None, page) -> str:
    """How Teams dates a chat's last message: today's time, "Yesterday", the weekday within
    the week ("Tue"), else d/m (a weekday a week back would read as the coming one)."""
    if at is None:  # no message yet
        return ""
    then, ago = days_ago(at, page)
    if ago == 0:
        return simclock.clock_time(at)
    if ago == 1:
        return "Yesterday"
    return f"{then:%a}" if ago < 7 else f"{then.day}/{then.month}"


@register.filter
def message_stamp(at: float, page) -> str:
    """A message's header time: "09:12", "Yesterday 17:30", "Mon 3/3 10:05"."""
    then, ago = days_ago(at, page)
    clock = simclock.clock_time(at)
    return {0: clock, 1: f"Yesterday {clock}"}.get(
        ago, f"{then:%a} {then.day}/{then.month} {clock}"
    )


@register.simple_tag
def reaction_choices() -> tuple[tuple[str, str], ...]:
    """The message toolbar's reactions: (name, label)."""
    return tuple((name, reaction_label(name)) for name in REACTIONS)


@register.filter
def reaction_label(name: str) -> str:
    return name.capitalize() if name in REACTIONS else name


@register.simple_tag(takes_context=True)
def when_text(context: template.Context, at: float | None, fallback: str = "") -> str:
    """A call or activity time on the page's clock ("5 min ago", "14:35", "Yesterday 16:00",
    "Mon 3 Mar": the day named once it is not today, so the feed never reads later than now),
    else the catalog's own words."""
    if at is None:
        return fallback
    return sim_relative(at, context["page"])
