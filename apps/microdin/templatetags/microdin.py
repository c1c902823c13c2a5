"""Template tags for MicroDin pages (repeated rows come from the kit: `{% load rows %}`)."""

from __future__ import annotations

import re

from django import template

register = template.Library()


@register.filter
def initials(name: str) -> str:
    return "".join(part[0] for part in re.split(r"\s+", name.strip())[:2] if part).upper()
