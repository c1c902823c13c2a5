"""Relevance search as Google Scholar's: words, not letters.

Every word of a query must occur in the paper — its title, authors, abstract or venue —, a word
matching its other forms ("notification" finds "notifications", Porter's stemmer); results go
by BM25 (SQLite's FTS5, in the standard library), a title match weighing most. Nonsense finds
nothing, as on the real site: the original's three-letter shingles found 18 papers for
"zzqqxxnothing" (its "nothing" shared "thi", "hin", "ing" with half the catalog). `similar`
asks for any of a title's words instead of all (a paper's related articles).
"""

from __future__ import annotations

import re
import sqlite3
from collections.abc import Iterable

from apps.microscholar.state import Paper

WORD = re.compile(r"\w+")
# Weights of the indexed columns for BM25, in table order: id (not searched), title, authors,
# abstract, venue.
WEIGHTS = (0.0, 10.0, 4.0, 1.0, 2.0)
# Words too common to make two titles related.
STOPWORDS = frozenset(
    [
        "a",
        "an",
        "and",
        "are",
        "as",
        "at",
        "by",
        "for",
        "from",
        "in",
        "into",
        "is",
        "of",
        "on",
        "or",
        "over",
        "the",
        "to",
        "under",
        "via",
        "with",
        "without",
    ]
)


def words(text: str) -> list[str]:
    return WORD.findall(text.lower())


def _matching(papers: Iterable[Paper], match: str) -> list[str]:
    """Ids of the papers matching the FTS5 expression `match`, best BM25 first (ties in the
    order given)."""
    with sqlite3.connect(":memory:") as db:
        db.execute(
            "CREATE VIRTUAL TABLE papers USING fts5(id UNINDEXED, title, authors, snippet, source,"
            " tokenize='porter unicode61 remove_diacritics 2')"
        )
        db.executemany(
            "INSERT INTO papers VALUES (?, ?, ?, ?, ?)",
            ((p.id, p.title, p.authors, p.snippet, p.source) for p in papers),
        )
        weights = ", ".join(str(w) for w in WEIGHTS)
        rows = db.execute(
            f"SELECT id FROM papers WHERE papers MATCH ? ORDER BY bm25(papers, {weights}), rowid",
            (match,),
        ).fetchall()
    return [paper_id for (paper_id,) in rows]


def _quoted(terms: Iterable[str]) -> list[str]:
    """Each word as an FTS5 string: what a user typed is never read as query syntax."""
    return ['"' + term.replace('"', '""') + '"' for term in terms]


def ranked(papers: Iterable[Paper], query: str) -> list[str]:
    """Ids of the papers holding every word of `query`, most relevant first; a query without
    words matches all, in the order given."""
    papers = list(papers)
    terms = words(query)
    if not terms:
        return [p.id for p in papers]
    return _matching(papers, " AND ".join(_quoted(terms)))


def similar(papers: Iterable[Paper], title: str) -> list[str]:
    """Ids of the papers sharing a meaningful word with `title`, most similar first."""
    terms = [term for term in words(title) if term not in STOPWORDS]
    if not terms:
        return []
    return _matching(papers, " OR ".join(_quoted(terms)))
