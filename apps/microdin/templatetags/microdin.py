"""Template tags for MicroDin pages: compact ages ("5m", "2h", "3d") and repeated rows.

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

register = template.Library()

MINUTE, HOUR, DAY, WEEK = 60, 3600, 86400, 7 * 86400
_BLANK_CSRF = 'name="csrfmiddlewaretoken" value=""'


def short_ago(at: float, now: float) -> str:
    """How long ago, as the network writes it: now, 5m, 2h, 3d, 1w."""
    elapsed = max(0.0, now - at)
    for unit, size in (("w", WEEK), ("d", DAY), ("h", HOUR), ("m", MINUTE)):
        if elapsed >= size:
            return f"{int(elapsed // size)}{unit}"
    return "now"


def short_ago_changes_at(at: float, now: float) -> float:
    """When `short_ago(at, now)` next reads differently: the next whole unit."""
    elapsed = max(0.0, now - at)
    size = next((s for s in (WEEK, DAY, HOUR, MINUTE) if elapsed >= s), MINUTE)
    return at + (elapsed // size + 1) * size


@register.filter
def ago(at: float, page) -> str:
    """`{{ post.posted_at|ago:page }}`; the page learns when the text next changes."""
    page.changes_at(short_ago_changes_at(at, page.now))
    return short_ago(at, page.now)


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
                page.changes_at(short_ago_changes_at(at, page.now))
            inputs["ago"] = short_ago(at, page.now) if at is not None else ""
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
