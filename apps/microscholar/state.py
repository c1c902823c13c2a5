"""The scholar's view of the index as immutable values, and the questions pages ask of it.

`Scholar` holds what has been indexed so far (papers and alerts, in arrival order) and what the
user did to them (saved, cited, read). Citation counts move with the clock: each paper's count is
a `Waypoints` series read at the one `now` of a request, so the page, its live push and the
evaluation tables show the same number at the same simulated instant.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass

from apps.kit.records import flag, from_catalog, text, text_or, texts, whole_number
from apps.kit.retractions import is_gone, present
from apps.kit.state import CatalogState
from apps.kit.streaming import no_items, shown_count
from apps.kit.waypoints import Waypoints

ENVIRONMENT = "microscholar"


@dataclass(frozen=True)
class Paper:
    """One indexed article (the catalog record as the site shows it)."""

    id: str
    title: str = from_catalog(text("title"))
    author_ids: tuple[str, ...] = from_catalog(texts("authorIds"))
    # display string, "C Taylor, H Marsh" (the eval column)
    authors: str = from_catalog(text("authors"))
    source: str = from_catalog(text("source"))
    year: int = from_catalog(whole_number("year"))
    # the abstract (the eval column is called snippet, as the original's)
    snippet: str = from_catalog(text("snippet"))
    citations: Waypoints  # "Cited by N" over simulated time
    pdf_source: str = from_catalog(text_or("pdfSource"), default="")
    is_book: bool = from_catalog(flag("isBook"), default=False)
    is_target: bool = from_catalog(flag("isTargetPaper"), default=False)
    task_type: str = from_catalog(text_or("taskType", "noise"), default="noise")
    versions: int = from_catalog(whole_number("versions", 1), default=1)
    indexed_at: float = 0.0  # simulated seconds
    gone_at: float | None = None  # withdrawn by its authors then (apps.kit.retractions)

    def cited_by(self, now: float) -> int:
        """ "Cited by N" at `now`, to the nearest whole citation (as `citations_change_at` counts)."""
        return shown_count(self.citations.value_at(now))

    def citations_change_at(self, now: float) -> float | None:
        return self.citations.next_change(now, step=1)


@dataclass(frozen=True)
class PaperState:
    saved: bool = False
    cited: bool = False  # the Cite dialog was opened (the original's isCited)


@dataclass(frozen=True)
class Alert:
    id: str
    type: str = from_catalog(text_or("type", "keyword"))  # citation | new_paper | keyword
    title: str = from_catalog(text("title"))
    description: str = from_catalog(text("description"))
    related_paper_id: str = from_catalog(text_or("relatedPaperId"), default="")
    arrived_at: float = 0.0


@dataclass(frozen=True)
class Scholar(CatalogState):
    papers: Mapping[str, Paper] = no_items()  # arrival order
    paper_states: Mapping[str, PaperState] = no_items()
    alerts: Mapping[str, Alert] = no_items()  # arrival order
    alert_read: Mapping[str, bool] = no_items()

    def is_saved(self, paper_id: str) -> bool:
        return self.paper_states.get(paper_id, PaperState()).saved

    def is_cited(self, paper_id: str) -> bool:
        return self.paper_states.get(paper_id, PaperState()).cited


empty_scholar = Scholar  # a catalog → the index before anything arrives


# --- counts (baselines, badges) ------------------------------------------------------------------


def listed(scholar: Scholar) -> list[Paper]:
    """The papers in the index: a withdrawn one has left results, profiles and the library."""
    return present(scholar.papers.values())


def is_listed(scholar: Scholar, paper_id: str) -> bool:
    paper = scholar.papers.get(paper_id)
    return paper is not None and not is_gone(paper)


def paper_count(scholar: Scholar) -> int:
    return len(listed(scholar))


def saved_paper_count(scholar: Scholar) -> int:
    return len(saved_ids(scholar))


def unread_alert_count(scholar: Scholar) -> int:
    return sum(1 for is_read in scholar.alert_read.values() if not is_read)


def target_paper_available(scholar: Scholar) -> int:
    return int(any(p.is_target for p in scholar.papers.values()))


def saved_ids(scholar: Scholar) -> list[str]:
    return [i for i, s in scholar.paper_states.items() if s.saved and is_listed(scholar, i)]


def newest_first(scholar: Scholar, ids: Iterable[str]) -> list[str]:
    """Latest indexed on top; equal times keep the later arrival first."""
    position = {paper_id: n for n, paper_id in enumerate(scholar.papers)}
    return sorted(ids, key=lambda i: (scholar.papers[i].indexed_at, position[i]), reverse=True)
