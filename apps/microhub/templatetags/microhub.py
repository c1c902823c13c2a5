"""Template tags for MicroHub pages. `label_style` colours a label pill as GitHub does (dark
text on light labels, white on dark). Repeated rows come from the kit (`{% load rows %}`,
`ago="long"`: "3 hours ago").
"""

from __future__ import annotations

from django import template
from django.utils.html import format_html
from django.utils.safestring import SafeString

from apps.microhub.markup import render_markdown

register = template.Library()


@register.filter
def label_style(color: str) -> str:
    """Inline style of a label pill: its colour, and text that stays readable on it."""
    hex_color = color.lstrip("#")
    if len(hex_color) != 6:
        return "background:#ededed;color:#1f2328"
    r, g, b = (int(hex_color[i : i + 2], 16) for i in (0, 2, 4))
    light = (0.299 * r + 0.587 * g + 0.114 * b) > 150
    return format_html("background:#{};color:{}", hex_color, "#1f2328" if light else "#fff")


@register.filter
def filesize(size: int) -> str:
    return f"{size} Bytes" if size < 1024 else f"{size / 1024:.1f} KB"


@register.filter
def duration(seconds: int) -> str:
    minutes, rest = divmod(int(seconds), 60)
    return f"{minutes}m {rest}s" if minutes else f"{rest}s"


@register.filter
def markdown(text: str) -> SafeString:
    """Comment and issue text through the safe Markdown subset (apps.microhub.markup)."""
    return render_markdown(text)


# Reactions by GitHub's names (our catalog) or as the emoji the original stored; drawn as icons
# because emoji render as empty boxes without an emoji font.
REACTIONS = {
    name: icon
    for icon, names in {
        "thumbs-up": ("+1", "👍"),
        "thumbs-down": ("-1", "👎"),
        "rocket": ("rocket", "🚀"),
        "party-popper": ("hooray", "🎉"),
        "heart": ("heart", "❤️"),
        "laugh": ("laugh", "😄"),
        "eye": ("eyes", "👀"),
    }.items()
    for name in names
}


@register.filter
def reaction(emoji: str) -> str:
    return REACTIONS.get(emoji, "smile")
