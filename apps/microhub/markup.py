"""A small, safe Markdown subset for READMEs, issue bodies and comments.

Why our own and not a library: the text is our catalog's and what the user types; this subset
(headings, paragraphs, bullet / numbered / task lists, fenced code, inline code, bold, italic,
links) is all of it uses, and it needs no new dependency. Safe by construction: every piece of
text is HTML-escaped before any markup is added, and a link keeps only an http(s), mailto or
relative target — no raw HTML, no `javascript:` URLs. A relative target is resolved as GitHub
does, against the folder of the file that holds it (`files`: the repository's blob URL of that
folder): `docs/api.md` in the README opens that file's page, not a 404.
"""

from __future__ import annotations

import functools
import posixpath
import re
from html import escape

from django.utils.safestring import SafeString, mark_safe

HEADING = re.compile(r"(#{1,6})\s+(.*)")
BULLET = re.compile(r"[-*]\s+(.*)")
NUMBERED = re.compile(r"\d+[.)]\s+(.*)")
TASK = re.compile(r"\[([ xX])\]\s+(.*)")
CODE_SPAN = re.compile(r"`([^`]+)`")
BOLD = re.compile(r"\*\*(.+?)\*\*")
ITALIC = re.compile(r"(?<![\w*])[*_]([^*_]+)[*_](?![\w*])")
LINK = re.compile(r"\[([^\]]+)\]\(([^)\s]+)\)")


def _target(target: str, files: str) -> str | None:
    """Where a link goes (None: nowhere a page may link to)."""
    lowered = target.lower()
    if lowered.startswith(("http://", "https://", "mailto:")):
        return target
    if ":" in target:
        return None
    if files and not target.startswith(("/", "#", "?")):
        blob, _, folder = files.partition("/blob/")
        path = posixpath.normpath(posixpath.join("/", folder, target)).lstrip("/")  # never above
        return f"{blob}/blob/{path}"
    return target


def inline(text: str, files: str = "") -> str:
    """One line of escaped text with inline markup (code spans are left alone inside)."""

    def link(match: re.Match) -> str:
        text, target = match.group(1), _target(match.group(2), files)
        return text if target is None else f'<a href="{target}" rel="nofollow noopener">{text}</a>'

    parts = CODE_SPAN.split(escape(text, quote=True))
    out = []
    for index, part in enumerate(parts):
        if index % 2:
            out.append(f"<code>{part}</code>")
        else:
            part = LINK.sub(link, part)
            part = BOLD.sub(r"<strong>\1</strong>", part)
            out.append(ITALIC.sub(r"<em>\1</em>", part))
    return "".join(out)


def _list_item(text: str, files: str) -> str:
    task = TASK.fullmatch(text)
    if task:
        checked = " checked" if task.group(1).lower() == "x" else ""
        return (
            f'<li class="task"><input type="checkbox" disabled{checked} aria-label="done"> '
            f"{inline(task.group(2), files)}</li>"
        )
    return f"<li>{inline(text, files)}</li>"


@functools.lru_cache(maxsize=1024)
def render_markdown(text: str, files: str = "") -> SafeString:
    """`text` as HTML (block by block); the same text is rendered once per process. `files`:
    the blob URL of the folder holding the text, which its relative links are resolved in
    (`…/blob/docs`); without it they are left as written."""
    html: list[str] = []
    paragraph: list[str] = []
    list_kind: str | None = None
    lines = iter(text.replace("\r\n", "\n").split("\n"))

    def close_paragraph() -> None:
        if paragraph:
            html.append(f"<p>{'<br>'.join(inline(line, files) for line in paragraph)}</p>")
            paragraph.clear()

    def close_list() -> None:
        nonlocal list_kind
        if list_kind:
            html.append(f"</{list_kind}>")
            list_kind = None

    for line in lines:
        stripped = line.strip()
        if stripped.startswith("```"):
            close_paragraph()
            close_list()
            code = []
            for inner in lines:
                if inner.strip().startswith("```"):
                    break
                code.append(inner)
            html.append(f"<pre><code>{escape(chr(10).join(code))}</code></pre>")
            continue
        heading, bullet, numbered = (
            HEADING.fullmatch(stripped),
            BULLET.fullmatch(stripped),
            NUMBERED.fullmatch(stripped),
        )
        if heading:
            close_paragraph()
            close_list()
            level = len(heading.group(1))
            html.append(f"<h{level}>{inline(heading.group(2), files)}</h{level}>")
        elif bullet or numbered:
            close_paragraph()
            kind = "ul" if bullet else "ol"
            if list_kind != kind:
                close_list()
                html.append(f"<{kind}>")
                list_kind = kind
            html.append(_list_item((bullet or numbered).group(1), files))
        elif not stripped:
            close_paragraph()
            close_list()
        else:
            close_list()
            paragraph.append(stripped)
    close_paragraph()
    close_list()
    return mark_safe("".join(html))
