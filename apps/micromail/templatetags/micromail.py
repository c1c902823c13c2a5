"""Template filters for MicroMail pages: simulated time and folder names."""

from __future__ import annotations

from django import template

from apps.micromail.simclock import ago, clock_time
from apps.micromail.state import FOLDER_TITLES

register = template.Library()


@register.filter
def sim_ago(at: float, now: float) -> str:
    return ago(at, now)


@register.filter
def sim_clock(at: float) -> str:
    return clock_time(at)


@register.filter
def folder_title(folder: str) -> str:
    return FOLDER_TITLES.get(folder, folder.title())

