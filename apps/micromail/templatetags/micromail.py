"""Template tags and filters for MicroMail pages: folder names, the message-list row, plus the
shared simulated-time filters (apps/agent_site/templatetags/simtime.py) so `{% load micromail %}`
is enough."""

from __future__ import annotations

from functools import lru_cache

from django import template
from django.template.loader import get_template
from django.utils.safestring import SafeString, mark_safe

from apps.agent_site import simclock
from apps.agent_site.templatetags.simtime import sim_ago, sim_clock
from apps.micromail.listing import Row
from apps.micromail.state import FOLDER_TITLES

register = template.Library()

# Rendered rows kept per process: about ten full mailboxes of the largest catalog.
ROW_CACHE_SIZE = 4096


register.filter("sim_ago", sim_ago)
register.filter("sim_clock", sim_clock)


@register.filter
def folder_title(folder: str) -> str:
    return FOLDER_TITLES.get(folder, folder.title())


@register.simple_tag(takes_context=True)
def message_rows(context: template.Context, rows: tuple[Row, ...]) -> SafeString:
    """The rows of the message list, each rendered by micromail/_row.html.

    Rows are most of a mailbox page's rendering, and the same row is shown over and over: on
    every screen it belongs to, on every reload and every live push. So a row is rendered once
    per distinct input and reused. The key holds everything the row template reads — the row
    (immutable message and state, its URL, whether it is open) and the few page values passed
    below — so a cached row is always the row a fresh render would give. The time is passed as
    its text ("5 min ago"), not as `now`, so a live clock keeps hitting the cache.
    """
    token, self_first_name = context["token"], context["self_first_name"]
    searches_everywhere = context["screen"].query.searches_everywhere
    now = context["page"].now
    return mark_safe(
        "".join(
            _render_row(
                row,
                token=token,
                self_first_name=self_first_name,
                searches_everywhere=searches_everywhere,
                ago=simclock.ago(row.email.arrived_at, now),
            )
            for row in rows
        )
    )


@lru_cache(maxsize=ROW_CACHE_SIZE)
def _render_row(
    row: Row, *, token: str, self_first_name: str, searches_everywhere: bool, ago: str
) -> SafeString:
    return get_template("micromail/_row.html").render(
        {
            "row": row,
            "token": token,
            "self_first_name": self_first_name,
            "searches_everywhere": searches_everywhere,
            "ago": ago,
        }
    )
