"""The original's relevance search: three-character shingles, containment score, 0.3 threshold.

A query matches a paper when at least 30% of the query's shingles occur in the shingles of
"title authors snippet source"; results go by score, best first (ties keep index order). So
"Jackson" finds "D Jackson" and a typo still finds its paper, as in the original.
"""

from __future__ import annotations

from collections.abc import Iterable

from apps.microscholar.state import Paper

MIN_SCORE = 0.3


def shingles(text: str, size: int = 3) -> frozenset[str]:
    """Lowercased, space-padded character shingles ("abc" → " ab", "abc", "bc ")."""
    padded = f" {text.lower()} "
    if len(padded.strip()) == 0:
        return frozenset()
    return frozenset(padded[i : i + size] for i in range(len(padded) - size + 1))


def containment(query: frozenset[str], paper: Paper) -> float:
    """The share of the (never empty) query's shingles found in "title authors snippet source"."""
    document = shingles(f"{paper.title} {paper.authors} {paper.snippet} {paper.source}")
    return len(query & document) / len(query)


def ranked(papers: Iterable[Paper], query: str) -> list[str]:
    """Ids of the papers matching `query`, best score first; a blank query matches all."""
    papers = list(papers)
    if not query.strip():
        return [p.id for p in papers]
    wanted = shingles(query.strip())
    scored = [(containment(wanted, p), n, p.id) for n, p in enumerate(papers)]
    return [i for score, _, i in sorted(scored, key=lambda s: (-s[0], s[1])) if score >= MIN_SCORE]
