"""The MicroScholar pages worth timing (`manage.py bench_pages --env microscholar`), relative to
the environment root. Opening the Cite dialog the first time cites the paper."""

from __future__ import annotations

import re
from urllib.parse import quote, urlencode

from apps.microscholar.state import Scholar

_WORD = re.compile(r"[A-Za-z]{6,}")


def sample_pages(scholar: Scholar) -> list[str]:
    pages = ["", "library", "alerts", "alerts?filter=unread"]
    if not scholar.papers:
        return pages
    paper = next(iter(scholar.papers.values()))
    word = max(_WORD.findall(paper.title) or ["learning"], key=len).lower()
    pages += [
        "?" + urlencode({"q": word}),
        "?" + urlencode({"q": word, "sort": "date"}),
        "?" + urlencode({"q": word, "as_ylo": paper.year}),
        "?start=10",
        f"papers/{quote(paper.id)}",
        f"papers/{quote(paper.id)}/cite",
    ]
    if paper.author_ids:
        pages.append("citations?" + urlencode({"user": paper.author_ids[0]}))
    return pages
