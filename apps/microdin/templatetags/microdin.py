"""Template tags for MicroDin pages: repeated rows, each with its compact age ("5m", "2h", "3d").

`{% rows "microdin/_post.html" cards "card" stamp="post.posted_at" %}` renders each item once
per distinct input (apps.agent_site.fragments): the row gets the item, the environment root and
its age as text, and nothing else of the page. Forms in rows carry a blank CSRF token that is
filled in once for the whole list, so a cached row serves every request.
"""

from __future__ import annotations

import re
from operator import attrgetter

from django import template
from django.utils.safestring import SafeString, mark_safe

from apps.agent_site.fragments import render_fragment
from apps.agent_site.simclock import compact_ago, units_changes_at

register = template.Library()

_BLANK_CSRF = 'name="csrfmiddlewaretoken" value=""'


@register.simple_tag(takes_context=True)
def rows(
    context: template.Context, template_name: str, items, name: str, stamp: str = "", **extra
) -> SafeString:
    """Each of `items` through `template_name` as `name`, with `root`, the `extra` inputs and
    (when `stamp` names the item's time attribute) its age as `ago`."""
    page, root = context["page"], context["root"]
    read_time = attrgetter(stamp) if stamp else None
    html = []
    for item in items:
        inputs = {name: item, "root": root, **extra}
        if read_time is not None:
            try:
                at = read_time(item)
            except AttributeError:  # nothing to date (a thread without messages yet)
                at = None
            if at is not None:
                page.changes_at(units_changes_at(at, page.now))
            inputs["ago"] = compact_ago(at, page.now) if at is not None else ""
        html.append(render_fragment(template_name, **inputs))
    return mark_safe(with_csrf_token("".join(html), str(context.get("csrf_token", ""))))


def with_csrf_token(html: str, token: str) -> str:
    """Fill the blank CSRF inputs of cached rows with this page's token."""
    return (
        html.replace(_BLANK_CSRF, f'name="csrfmiddlewaretoken" value="{token}"') if token else html
    )


@register.filter
def initials(name: str) -> str:
    return "".join(part[0] for part in re.split(r"\s+", name.strip())[:2] if part).upper()
