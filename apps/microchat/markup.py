"""A message's light markdown as HTML: **bold**, _italic_, `code`, [links](url), bare URLs and
@mentions (the self user's highlighted more strongly), everything else escaped.

Pure and cached per (text, self names): the same message renders the same everywhere.
"""

from __future__ import annotations

import functools
import re

from django.utils.html import escape
from django.utils.safestring import SafeString, mark_safe

# One pass over the text; the first alternative that matches at a position wins.
TOKEN = re.compile(
    r"`(?P<code>[^`\n]+)`"
    r"|\*\*(?P<bold>[^*\n]+)\*\*"
    r"|(?<![\w])_(?P<italic>[^_\n]+)_(?![\w])"
    r"|\[(?P<label>[^\]\n]+)\]\((?P<href>https?://[^\s)]+)\)"
    r"|(?P<url>https?://[^\s<>()]+[^\s<>().,;:!?])"
    r"|(?<![\w@])@(?P<mention>you\b|[A-Z][\w'-]*(?: [A-Z][\w'-]*)?)"
)
TAGS = {"code": "code", "bold": "strong", "italic": "em"}  # the token → the element it becomes


def _link(href: str, label: str) -> str:
    return f'<a href="{escape(href)}" target="_blank" rel="noopener noreferrer">{escape(label)}</a>'


def _mention(name: str, self_names: tuple[str, ...]) -> str:
    mine = name == "you" or name in self_names
    shown = self_names[0] if name == "you" and self_names else name
    css = "mention me" if mine else "mention"
    return f'<span class="{css}">@{escape(shown)}</span>'


@functools.lru_cache(maxsize=4096)
def render_markup(text: str, self_names: tuple[str, ...] = ()) -> SafeString:
    """`self_names`: how the self user may be @mentioned (full name first, then first name);
    the original's "@you" shows as the full name."""
    out, position = [], 0
    for match in TOKEN.finditer(text):
        out.append(escape(text[position : match.start()]))
        kind = match.lastgroup
        if kind in TAGS:
            out.append(f"<{TAGS[kind]}>{escape(match[kind])}</{TAGS[kind]}>")
        elif kind in ("label", "href"):
            out.append(_link(match["href"], match["label"]))
        elif kind == "url":
            out.append(_link(match["url"], match["url"]))
        else:
            out.append(_mention(match["mention"], self_names))
        position = match.end()
    out.append(escape(text[position:]))
    return mark_safe("".join(out).replace("\n", "<br>"))
