"""The scholar's view of the index as immutable values, and the questions pages ask of it.

`Scholar` holds what has been indexed so far (papers and alerts, in arrival order) and what the
user did to them (saved, cited, read). Citation counts move with the clock: each paper's count is
a `Waypoints` series read at the one `now` of a request, so the page, its live push and the
evaluation tables show the same number at the same simulated instant.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass

from apps.kit.retractions import is_gone, present
from apps.kit.state import CatalogState
from apps.kit.streaming import no_items, shown_count
from apps.kit.waypoints import Waypoints

ENVIRONMENT = "microscholar"


@dataclass(frozen=True)
class Paper:
    """One indexed article (the catalog record as the site shows it)."""

    id: str
    title: str
    author_ids: tuple[str, ...]
    authors: str  # display string, "C Taylor, H Marsh" (the eval column)
    source: str
    year: int
    snippet: str  # the abstract (the eval column is called snippet, as the original's)
    citations: Waypoints  # "Cited by N" over simulated time
    pdf_source: str = ""
    is_book: bool = False
    is_target: bool = False
    task_type: str = "noise"
    versions: int = 1
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
    type: str  # citation | new_paper | keyword
    title: str
    description: str
    related_paper_id: str = ""
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
