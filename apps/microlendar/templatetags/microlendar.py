"""Template tags for MicroLendar pages: event chips and time-grid blocks, each rendered once per
distinct input (apps.kit.fragments), and the hour labels of the time grid."""

from __future__ import annotations

from django import template
from django.utils.safestring import SafeString, mark_safe

from apps.kit.fragments import render_fragment
from apps.microlendar import times
from apps.microlendar.screens import Block, Chip

register = template.Library()

HOURS = tuple((hour, times.hour_label(hour)) for hour in range(24))


@register.simple_tag
def hour_rows() -> tuple[tuple[int, str], ...]:
    return HOURS


@register.simple_tag(takes_context=True)
def event_chips(
    context: template.Context, chips: tuple[Chip, ...], style: str = "month"
) -> SafeString:
    """Events as links in a month cell (`style="month"`), the schedule or search results
    (`style="agenda"`): microlendar/_chip.html, cached per (chip, root, style)."""
    root = context["root"]
    return mark_safe(
        "".join(
            render_fragment("microlendar/_chip.html", chip=c, root=root, style=style) for c in chips
        )
    )


@register.simple_tag(takes_context=True)
def event_blocks(context: template.Context, blocks: tuple[Block, ...]) -> SafeString:
    """Events placed in a day column: microlendar/_block.html, cached per (block, root)."""
    root = context["root"]
    return mark_safe(
        "".join(render_fragment("microlendar/_block.html", block=b, root=root) for b in blocks)
    )


@register.filter
def clock_label(minutes: int) -> str:
    return times.label(minutes)


@register.filter
def hhmm(minutes: int) -> str:
    return times.hhmm(minutes)
