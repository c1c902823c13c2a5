"""Template filters for MicroMail pages: folder names, plus the shared simulated-time filters
(apps/agent_site/templatetags/simtime.py) so `{% load micromail %}` is enough."""

from __future__ import annotations

from django import template

from apps.agent_site.templatetags.simtime import sim_ago, sim_clock
from apps.micromail.state import FOLDER_TITLES

register = template.Library()


register.filter("sim_ago", sim_ago)
register.filter("sim_clock", sim_clock)


@register.filter
def folder_title(folder: str) -> str:
    return FOLDER_TITLES.get(folder, folder.title())

