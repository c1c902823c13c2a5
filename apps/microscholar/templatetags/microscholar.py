"""Template tags for MicroScholar pages: result entries rendered once per distinct input."""

from __future__ import annotations

from django import template
from django.utils.safestring import SafeString, mark_safe

from apps.kit.fragments import render_fragment
from apps.microscholar.screens import Row

register = template.Library()


@register.simple_tag(takes_context=True)
def result_rows(context: template.Context, rows: tuple[Row, ...]) -> SafeString:
    """Each result entry through microscholar/_row.html (apps.kit.fragments): a row's
    inputs include its "Cited by" count as read at the page's `now`, so a count that ticks over
    renders anew and the others come from the cache."""
    token = context["token"]
    return mark_safe(
        "".join(render_fragment("microscholar/_row.html", row=r, token=token) for r in rows)
    )
