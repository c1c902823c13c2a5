"""MicroScholar's registration with the core: scenario events, baselines, evaluation tables.

Scenario events (SentinelBench format):
- `preload_papers {paper_ids, alert_ids, saved_paper_ids?}` — the index and alerts when the task
  starts (`["*"]` = a whole catalog table); papers in `saved_paper_ids` start in the library.
  Alerts keep their catalogued read state. Baselines are measured right after it.
- `new_paper {paper_id}` (and its original twin `inject_target_paper`) — a paper is indexed.
- `new_alert {alert_id}` — an alert arrives, unread.

Unlike the original (a KeyError that aborted the event), an id missing from the catalog is
skipped, as in every other environment; scenario validation names it to the author.
"""

from __future__ import annotations

import json
import sqlite3
from collections.abc import Mapping
from types import MappingProxyType

from pydantic import Field

from apps.kit.legacy_tables import Table
from apps.microscholar import state as index
from apps.microscholar.actions import ACTIONS
from apps.microscholar.bench import sample_pages
from apps.microscholar.catalog import (
    catalog_alert,
    catalog_alert_read,
    catalog_paper,
    coauthor_pairs,
)
from apps.microscholar.state import (
    ENVIRONMENT,
    PaperState,
    Scholar,
    empty_scholar,
    with_alerts,
    with_papers,
)
from events.registry import Environment, EventType, ImplicitAction, LoggedEvent, Measure, timeless
from events.schemas import Payload

# The original's metric names (eval_sql reads baseline_<name> from session_meta).
BASELINES: Mapping[str, Measure] = MappingProxyType(
    {
        "target_paper_available": timeless(index.target_paper_available),
        "paper_count": timeless(index.paper_count),
        "saved_paper_count": timeless(index.saved_paper_count),
        "unread_alert_count": timeless(index.unread_alert_count),
    }
)


def index_papers(
    scholar: Scholar, paper_ids: list[str], *, at: float, saved: frozenset[str] = frozenset()
) -> Scholar:
    """Index catalog papers at `at`. A paper already indexed is left as the user has it (no
    duplicate, no reset of saved/cited); unknown ids are skipped."""
    arrivals = []
    for paper_id in dict.fromkeys(paper_ids):
        if scholar.has_paper(paper_id):
            continue
        paper = catalog_paper(scholar.catalog, paper_id, indexed_at=at)
        if paper is not None:
            arrivals.append((paper, PaperState(saved=paper_id in saved)))
    return with_papers(scholar, arrivals) if arrivals else scholar


def deliver_alerts(
    scholar: Scholar, alert_ids: list[str], *, at: float, preloaded: bool
) -> Scholar:
    """Alerts arrive; preloaded ones keep their catalogued read state, new ones are unread."""
    arrivals = []
    for alert_id in dict.fromkeys(alert_ids):
        if alert_id in scholar.alerts:
            continue
        alert = catalog_alert(scholar.catalog, alert_id, arrived_at=at)
        if alert is not None:
            is_read = preloaded and catalog_alert_read(scholar.catalog, alert_id)
            arrivals.append((alert, is_read))
    return with_alerts(scholar, arrivals) if arrivals else scholar


def reduce_preload(scholar: Scholar, event: LoggedEvent) -> Scholar:
    payload, catalog = event.payload, scholar.catalog
    saved = frozenset(payload.get("saved_paper_ids") or ())
    paper_ids = catalog.expand(ENVIRONMENT, "papers", payload.get("paper_ids"))
    scholar = index_papers(scholar, paper_ids, at=event.at, saved=saved)
    alert_ids = catalog.expand(ENVIRONMENT, "alerts", payload.get("alert_ids"))
    return deliver_alerts(scholar, alert_ids, at=event.at, preloaded=True)


def reduce_new_paper(scholar: Scholar, event: LoggedEvent) -> Scholar:
    return index_papers(scholar, [event.payload["paper_id"]], at=event.at)


def reduce_new_alert(scholar: Scholar, event: LoggedEvent) -> Scholar:
    return deliver_alerts(scholar, [event.payload["alert_id"]], at=event.at, preloaded=False)


class PreloadPapers(Payload):
    paper_ids: list[str] = Field([], description='catalog paper ids; ["*"] = every paper')
    alert_ids: list[str] = Field([], description='catalog alert ids; ["*"] = every alert')
    saved_paper_ids: list[str] = Field([], description="papers already in the library")


class NewPaper(Payload):
    paper_id: str = Field(description="catalog paper id")


class NewAlert(Payload):
    alert_id: str = Field(description="catalog alert id")


NEW_PAPER = EventType(
    schema=NewPaper,
    reduce=reduce_new_paper,
    help="A paper is indexed: it shows in results, recommendations and profiles.",
    catalog_refs={"paper_id": "papers"},
)

EVENT_TYPES: Mapping[str, EventType] = MappingProxyType(
    {
        "preload_papers": EventType(
            schema=PreloadPapers,
            reduce=reduce_preload,
            help="Papers, alerts and the saved library at the start; baselines are measured after it.",
            catalog_refs={
                "paper_ids": "papers",
                "alert_ids": "alerts",
                "saved_paper_ids": "papers",
            },
            preload=True,
        ),
        "new_paper": NEW_PAPER,
        "inject_target_paper": NEW_PAPER,  # the original's duplicate of new_paper
        "new_alert": EventType(
            schema=NewAlert,
            reduce=reduce_new_alert,
            help="An alert arrives, unread.",
            catalog_refs={"alert_id": "alerts"},
        ),
    }
)


# --- evaluation tables (the original's names and columns; citedBy is ours, as of `now`) ---------

PAPERS = Table(
    "papers",
    (
        "id TEXT PRIMARY KEY",
        "title TEXT",
        "authors TEXT",
        "year INTEGER",
        "isTargetPaper INTEGER",
        "taskType TEXT",
        "snippet TEXT",
        "source TEXT",
        "citedBy INTEGER",
    ),
)
PAPER_STATES = Table(
    "paper_states", ("paper_id TEXT PRIMARY KEY", "isSaved INTEGER", "isCited INTEGER")
)
ALERTS = Table(
    "alerts",
    ("id TEXT PRIMARY KEY", "type TEXT", "title TEXT", "description TEXT", "relatedPaperId TEXT"),
)
ALERT_STATES = Table("alert_states", ("alert_id TEXT PRIMARY KEY", "isRead INTEGER"))
COAUTHORS = Table("coauthors", ("authorId1 TEXT", "authorId2 TEXT", "sharedPapers TEXT"))


def materialize(scholar: Scholar, now: float, conn: sqlite3.Connection) -> None:
    """The evaluation tables at `now`: citation counts are read at that instant."""
    PAPERS.write(
        conn,
        (
            (
                p.id,
                p.title,
                p.authors,
                p.year,
                p.is_target,
                p.task_type,
                p.snippet,
                p.source,
                p.cited_by(now),
            )
            for p in scholar.papers.values()
        ),
    )
    PAPER_STATES.write(conn, ((i, s.saved, s.cited) for i, s in scholar.paper_states.items()))
    ALERTS.write(
        conn,
        (
            (a.id, a.type, a.title, a.description, a.related_paper_id)
            for a in scholar.alerts.values()
        ),
    )
    ALERT_STATES.write(conn, scholar.alert_read.items())
    COAUTHORS.write(
        conn,
        (
            (one, two, json.dumps(list(shared)))
            for one, two, shared in coauthor_pairs(scholar.catalog)
        ),
    )


MICROSCHOLAR = Environment(
    name=ENVIRONMENT,
    title="MicroScholar",
    initial_state=empty_scholar,
    event_types=EVENT_TYPES,
    actions=ACTIONS,
    baselines=BASELINES,
    materialize=materialize,
    urlconf="apps.microscholar.urls",
    implicit_actions=(
        # Opening the Cite dialog is what records a citation in the original (no confirmation).
        ImplicitAction(
            page="cite",
            param="paper_id",
            action="cite",
            payload=lambda paper_id: {"paper_id": paper_id},
            applies=lambda scholar, paper_id: (
                scholar.has_paper(paper_id) and not scholar.is_cited(paper_id)
            ),
        ),
    ),
    sample_pages=sample_pages,
)
