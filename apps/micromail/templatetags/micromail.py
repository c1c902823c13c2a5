"""Template tags and filters for MicroMail pages: folder names, the message-list row, plus the
shared simulated-time filters (apps/kit/templatetags/simtime.py) so `{% load micromail %}`
is enough."""

from __future__ import annotations

from django import template
from django.utils.safestring import SafeString, mark_safe

from apps.kit import simclock
from apps.kit.fragments import render_fragment
from apps.kit.templatetags.simtime import sim_ago, sim_clock
from apps.micromail.screens import Row, row_label
from apps.micromail.state import FOLDER_TITLES

register = template.Library()

register.filter("sim_ago", sim_ago)
register.filter("sim_clock", sim_clock)


@register.filter
def folder_title(folder: str) -> str:
    return FOLDER_TITLES.get(folder, folder.title())


_FILE_KINDS = {
    "pdf": "pdf",
    **dict.fromkeys(("doc", "docx", "txt", "md", "rtf", "odt"), "doc"),
    **dict.fromkeys(("xls", "xlsx", "csv", "numbers"), "sheet"),
    **dict.fromkeys(("ppt", "pptx", "key"), "slides"),
    **dict.fromkeys(("png", "jpg", "jpeg", "gif", "webp", "svg"), "image"),
    **dict.fromkeys(("zip", "7z", "tar", "gz"), "archive"),
}


@register.filter
def file_kind(name: str) -> str:
    """The colour class of a file's icon, from its extension (Office's: red PDF, blue Word…)."""
    extension = name.rsplit(".", 1)[-1].lower() if "." in name else ""
    return _FILE_KINDS.get(extension, "file")


@register.simple_tag(takes_context=True)
def message_rows(context: template.Context, rows: tuple[Row, ...]) -> SafeString:
    """The rows of the message list, each rendered once per distinct input by
    micromail/_row.html (apps.kit.fragments). The arrival time goes in as its text, and
    the page learns when that text next changes, so a live list re-renders on the minute."""
    page = context["page"]
    inputs = {
        "token": context["token"],
        "self_first_name": context["self_first_name"],
        "searches_everywhere": context["screen"].query.searches_everywhere,
    }
    html = []
    for row in rows:
        arrived = row.email.arrived_at
        page.changes_at(simclock.ago_changes_at(arrived, page.now))
        ago = simclock.ago(arrived, page.now)
        label = row_label(row.email, row.state, ago)
        html.append(render_fragment("micromail/_row.html", row=row, ago=ago, label=label, **inputs))
    return mark_safe("".join(html))
