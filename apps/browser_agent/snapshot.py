"""A page as wait_for sees it: its visible text as markdown, one snapshot per check.

wait_for diffs two snapshots line by line, so a snapshot must hold only what a person could
read and must come out the same for two renders of the same state: scripts, styles, inline
SVG (icons and pictures as path data), unrendered templates, `hidden` elements and what a
closed `<details>` folds away (a menu's items, until its summary is clicked) are dropped, the
`<head>` too (none of it is on the page), and runs of blank lines are collapsed
so whitespace in the markup never reads as a change.
"""

from __future__ import annotations

import re

from bs4 import BeautifulSoup, Tag
from markdownify import ATX, MarkdownConverter

# Never on screen: code, styling, vector data, inert templates, and what only a browser
# without JavaScript would show.
INVISIBLE_TAGS = ("head", "script", "style", "svg", "template", "noscript")

_BLANK_RUNS = re.compile(r"\n[ \t]*(?:\n[ \t]*)+")

# ATX headings ("# Inbox") keep each heading on one line: underlined ones put a rule of `=`
# under it whose length follows the text, a second changed line for every changed heading.
_CONVERTER = MarkdownConverter(heading_style=ATX, bullets="-")


def html_to_markdown(html: str) -> str:
    """The page's visible text as markdown: no scripts, styles, SVG, templates, hidden
    elements or closed `<details>` content; trailing spaces stripped and blank lines collapsed, so the same state always
    gives the same text."""
    soup = BeautifulSoup(html, "html.parser")
    for element in soup.find_all(INVISIBLE_TAGS):
        element.decompose()
    for element in soup.find_all(hidden=True):
        element.decompose()
    for closed in soup.find_all("details", open=False):
        for folded in list(closed.contents):  # its text too, not only its elements
            if not (isinstance(folded, Tag) and folded.name == "summary"):
                folded.extract()
    markdown = _CONVERTER.convert_soup(soup)
    lines = (line.rstrip() for line in markdown.splitlines())
    return _BLANK_RUNS.sub("\n\n", "\n".join(lines)).strip() + "\n"
