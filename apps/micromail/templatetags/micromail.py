"""Template filters for MicroMail pages: folder names, file kinds, a message row's accessible
name. Simulated time comes from the shared `simtime` filters, message rows from `rows`."""

from __future__ import annotations

from django import template

from apps.micromail import screens
from apps.micromail.state import FOLDER_TITLES

register = template.Library()
register.filter("file_kind", screens.file_kind)


@register.filter
def folder_title(folder: str) -> str:
    return FOLDER_TITLES.get(folder, folder.title())


@register.filter
def row_label(row: screens.Row, ago: str) -> str:
    """The row link's accessible name, given its arrival time as the list shows it."""
    return screens.row_label(row.email, row.state, ago)
