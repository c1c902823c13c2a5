"""The Cite dialog: a paper in five citation styles, and the export files behind its links.

Pure functions of a paper and its authors' names. Names come from the people records when the
paper's author ids resolve; otherwise from the display string ("C Taylor" → initial "C").
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

from apps.microscholar.state import Paper

# format → (link text, file extension, media type)
EXPORTS: dict[str, tuple[str, str, str]] = {
    "bibtex": ("BibTeX", "bib", "application/x-bibtex"),
    "endnote": ("EndNote", "enw", "application/x-endnote-refer"),
    "refman": ("RefMan", "ris", "application/x-research-info-systems"),
    "refworks": ("RefWorks", "txt", "text/plain"),
}


@dataclass(frozen=True)
class Name:
    given: str  # a full first name, or an initial
    family: str

    @property
    def initials(self) -> str:
        return " ".join(f"{part[0]}." for part in self.given.split() if part)

    @property
    def inverted(self) -> str:
        return f"{self.family}, {self.given}"

    @property
    def natural(self) -> str:
        return f"{self.given} {self.family}"


def author_names(paper: Paper, catalog: Any) -> tuple[Name, ...]:
    shown = [a.strip() for a in paper.authors.split(",") if a.strip()]
    people = [catalog.users.get(i) for i in paper.author_ids]
    if people and all(people) and len(people) >= len(shown):
        full = [str(p.get("name", "")).split() for p in people]
        return tuple(Name(" ".join(parts[:-1]), parts[-1]) for parts in full if parts)
    names = []
    for display in shown:
        parts = display.split()
        names.append(Name(" ".join(parts[:-1]), parts[-1]) if len(parts) > 1 else Name("", display))
    return tuple(names)


def _join(items: list[str], last: str) -> str:
    if len(items) <= 1:
        return "".join(items)
    return ", ".join(items[:-1]) + f"{',' if len(items) > 2 else ''} {last} " + items[-1]


def mla(paper: Paper, names: tuple[Name, ...]) -> str:
    if not names:
        who = ""
    elif len(names) == 1:
        who = names[0].inverted
    elif len(names) == 2:
        who = f"{names[0].inverted}, and {names[1].natural}"
    else:
        who = f"{names[0].inverted}, et al"
    return f'{who}. "{paper.title}." {paper.source}, {paper.year}.'


def apa(paper: Paper, names: tuple[Name, ...]) -> str:
    people = [f"{n.family}, {n.initials}".strip(", ") for n in names]
    who = _join(people, "&")
    return f"{who} ({paper.year}). {paper.title}. {paper.source}."


def chicago(paper: Paper, names: tuple[Name, ...]) -> str:
    people = [names[0].inverted] + [n.natural for n in names[1:]] if names else []
    return f'{_join(people, "and")}. "{paper.title}." {paper.source} ({paper.year}).'


def harvard(paper: Paper, names: tuple[Name, ...]) -> str:
    people = [f"{n.family}, {n.initials}".strip(", ") for n in names]
    return f"{_join(people, 'and')} ({paper.year}) '{paper.title}', {paper.source}."


def bibtex_key(paper: Paper, names: tuple[Name, ...]) -> str:
    family = re.sub(r"[^a-z]", "", names[0].family.lower()) if names else "anon"
    word = next((w for w in re.findall(r"[a-z]+", paper.title.lower()) if len(w) > 3), "paper")
    return f"{family}{paper.year}{word}"


def bibtex(paper: Paper, names: tuple[Name, ...]) -> str:
    kind = "book" if paper.is_book else ("article" if paper.source == "arXiv" else "inproceedings")
    venue = "journal" if kind == "article" else ("publisher" if kind == "book" else "booktitle")
    authors = " and ".join(n.inverted for n in names)
    return (
        f"@{kind}{{{bibtex_key(paper, names)},\n"
        f"  title={{{paper.title}}},\n"
        f"  author={{{authors}}},\n"
        f"  {venue}={{{paper.source}}},\n"
        f"  year={{{paper.year}}}\n}}"
    )


# The dialog's styles, in its order.
STYLES = {"MLA": mla, "APA": apa, "Chicago": chicago, "Harvard": harvard, "BibTeX": bibtex}


def styles(paper: Paper, names: tuple[Name, ...]) -> tuple[tuple[str, str], ...]:
    return tuple((style, make(paper, names)) for style, make in STYLES.items())


# The tagged export formats: (record type, tags of title, each author, source, year, end line).
TAGGED = {
    "endnote": ("%0 Conference Paper", "%T", "%A", "%B", "%D", None),
    "refman": ("TY  - CONF", "T1  -", "AU  -", "T2  -", "PY  -", "ER  -"),
    "refworks": ("RT Conference Proceedings", "T1", "A1", "JF", "YR", None),
}


def export(paper: Paper, names: tuple[Name, ...], fmt: str) -> str:
    """The file behind an export link (`fmt` one of EXPORTS)."""
    if fmt == "bibtex":
        return bibtex(paper, names) + "\n"
    if fmt not in TAGGED:
        raise ValueError(f"format={fmt!r} is not valid; allowed: {', '.join(EXPORTS)}")
    kind, title, author, source, year, end = TAGGED[fmt]
    lines = [kind, f"{title} {paper.title}", *(f"{author} {n.inverted}" for n in names)]
    lines += [f"{source} {paper.source}", f"{year} {paper.year}", *([end] if end else [])]
    return "\n".join(lines) + "\n"
