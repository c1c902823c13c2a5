"""The text a person sees on a rendered page: what "the page changed" means to a watcher.

Used to check that a scenario's trigger shows on the page its prompt names
(apps.scenarios.watching), and to push a live re-render only when it reads differently
(apps.kit.consumers). Markup, attributes, scripts, hidden elements and the shell's own clock
are not text a watcher compares: the clock changes every minute whatever happens.

Pages are read by libxml2's HTML parser (lxml), which calls `_Text` for each tag and run of
text. It gives the standard library's `html.parser` results to the character on 949 pages of
the ten environments (text and signature alike) in 29 % of the time: a live push's
signature of MicroMail's full inbox (300 KB) is read once per render, in the render's thread.
"""

from __future__ import annotations

import re

from lxml import etree

# Never shown as text: the head, scripts and styles, templates, the icon sprite's symbols.
_SKIPPED = frozenset({"head", "script", "style", "template", "noscript", "symbol", "title"})
_VOID = frozenset(
    {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source", "wbr"}
)
# The shell's simulated clock (templates/site/base.html) reads the time, not what happened.
CLOCK_ID = "sim-clock"
_SPACE = re.compile(r"\s+")


class _Text:
    """What is seen, gathered as the parser reads (lxml's parser-target interface)."""

    def __init__(self, skip_ids: tuple[str, ...] = (CLOCK_ID,), pictures: bool = False) -> None:
        self.parts: list[str] = []
        self.open: list[str] = []  # tags open inside a skipped element, outermost first
        self.skip_ids = skip_ids
        # For a push's signature: what is seen without being text — a picture (its address),
        # an icon (its name), how an element is styled (its classes: bold when unread) — and
        # what pressing does: where a link leads, where a form posts (a viewer's "Next" arrow
        # that now skips an expired story reads the same but goes elsewhere).
        self.pictures = pictures

    def start(self, tag: str, named: dict[str, str]) -> None:
        if self.pictures and not self.open:
            if tag == "img":
                self.parts.append(f" [img {named.get('src') or ''}] ")
            elif tag == "use":
                self.parts.append(f" [icon {named.get('href') or ''}] ")
            elif tag == "a" and named.get("href"):
                self.parts.append(f"[→ {named['href']}]")
            elif tag == "form" and named.get("action"):
                self.parts.append(f"[⇢ {named['action']}]")
            if named.get("class"):
                self.parts.append(f"[.{named['class']}]")
        if tag in _VOID:
            return
        if self.open:
            self.open.append(tag)
            return
        if (
            tag in _SKIPPED
            or "hidden" in named  # aria-hidden text is still seen: only `hidden` hides
            or named.get("id") in self.skip_ids
        ):
            self.open.append(tag)
        elif tag in ("br", "p", "div", "li", "tr", "h1", "h2", "h3", "h4", "section"):
            self.parts.append(" ")

    def end(self, tag: str) -> None:
        if tag in _VOID:  # the parser closes what has no end tag: nothing was opened
            return
        if self.open:
            # Close up to the matching tag (HTML lets some end tags be left out).
            if tag in self.open:
                while self.open and self.open.pop() != tag:
                    pass
            return
        self.parts.append(" ")

    def data(self, data: str) -> None:
        if not self.open:
            self.parts.append(data)

    def close(self) -> str:
        return _SPACE.sub(" ", "".join(self.parts)).strip()


def _read(html: str, seen: _Text) -> str:
    # A fragment comes back wrapped in <html><body>: tags that only add spaces between words.
    parser = etree.HTMLParser(target=seen, no_network=True)
    parser.feed(html)
    return parser.close()


def visible_text(html: str) -> str:
    """The page's (or fragment's) text in document order, whitespace collapsed to one space."""
    return _read(html, _Text())


def visible_signature(html: str) -> str:
    """What a person sees of `html`: its text, the shell's clock included, its pictures, icons
    and styling (classes), and what pressing does (where links lead, where forms post); not its
    other attributes for machines (ids, data-*, CSRF tokens, labels). A live push that would not
    change it is not sent (apps.kit.consumers)."""
    return _read(html, _Text(skip_ids=(), pictures=True))


def text_difference(before: str, after: str, *, width: int = 60) -> str:
    """Where two texts first differ, as a short one-line excerpt of each ("" when equal)."""
    if before == after:
        return ""
    start = next(
        (i for i, (a, b) in enumerate(zip(before, after, strict=False)) if a != b),
        min(len(before), len(after)),
    )
    lo = max(0, start - 20)
    return f"before …{before[lo : lo + width]!r}… after …{after[lo : lo + width]!r}…"
