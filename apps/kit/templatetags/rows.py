"""Repeated rows of a page (posts, issues, cards), each rendered once per distinct input.

    {% load rows %}
    {% rows "microdin/_post.html" cards "card" stamp="post.posted_at" %}
    {% rows "microhub/_issue_row.html" issues "issue" stamp="opened_at" ago="long" %}
    {% row "microgram/_post.html" card=card at=card.post.posted_at %}

Each row goes through `apps.kit.fragments.render_fragment` with exactly: the item (under
`name`) or the named inputs, the environment `root`, the page's `csrf_token` (a placeholder in a
page rendered by `render_screen`, filled per response, so forms in rows are cacheable), any extra
inputs, and — when the row has a time (`stamp` names the item's attribute, or `at` is given) —
its age as text in `ago`, in one of the `simclock` styles. The page learns when that text next
changes, so a live page is pushed again then and a kept screen is not served past it.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from datetime import date
from operator import attrgetter
from typing import Any

from django import template
from django.utils.safestring import SafeString, mark_safe

from apps.kit import simclock
from apps.kit.fragments import render_fragment

register = template.Library()

# style → (text, when it next changes), of (at, now, the run's day zero)
Age = Callable[[float, float, date], Any]
AGES: dict[str, tuple[Age, Age]] = {
    # now · 5m · 2h · 3d · 1w
    "compact": (
        lambda at, now, _: simclock.compact_ago(at, now),
        lambda at, now, _: simclock.units_changes_at(at, now),
    ),
    # 3 hours ago · 2 weeks ago
    "long": (
        lambda at, now, _: simclock.long_ago(at, now),
        lambda at, now, _: simclock.units_changes_at(at, now),
    ),
    # just now · 5 min ago · 08:55 · Yesterday 17:30 · Mon 16 Nov (a mail client's list)
    "mail": (simclock.relative, simclock.relative_changes_at),
}


def _age(page, at: float, style: str) -> str:
    try:
        text, changes_at = AGES[style]
    except KeyError:
        raise template.TemplateSyntaxError(f"ago={style!r}: allowed {', '.join(AGES)}") from None
    zero = simclock.day_zero(getattr(page, "run", None))
    page.ages_at(changes_at(at, page.now, zero))
    return text(at, page.now, zero)


def _shared(context: template.Context) -> dict[str, Any]:
    return {"root": context["root"], "csrf_token": str(context.get("csrf_token", ""))}


@register.simple_tag(takes_context=True)
def rows(
    context: template.Context,
    template_name: str,
    items: Iterable,
    name: str,
    stamp: str = "",
    ago: str = "compact",
    **extra: Any,
) -> SafeString:
    """Each of `items` through `template_name` as `name`; with `stamp`, its age as `ago` text
    (an item without that attribute, or with None, gets "")."""
    page, shared = context["page"], _shared(context)
    read_time = attrgetter(stamp) if stamp else None
    html = []
    for item in items:
        inputs = {name: item, **shared, **extra}
        if read_time is not None:
            try:
                at = read_time(item)
            except AttributeError:  # nothing to date (a thread without messages yet)
                at = None
            inputs["ago"] = _age(page, at, ago) if at is not None else ""
        html.append(render_fragment(template_name, **inputs))
    return mark_safe("".join(html))


@register.simple_tag(takes_context=True)
def row(
    context: template.Context,
    template_name: str,
    at: float | None = None,
    ago: str = "compact",
    **inputs: Any,
) -> SafeString:
    """One row through `template_name` with the named `inputs`; with `at`, its age as text."""
    extra = _shared(context)
    if at is not None:
        extra["ago"] = _age(context["page"], at, ago)
    return render_fragment(template_name, **inputs, **extra)
