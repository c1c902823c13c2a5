"""MicroScholar's registration with the core: scenario events, baselines, evaluation tables.

Scenario events (SentinelBench format):
- `preload_papers {paper_ids, alert_ids, saved_paper_ids?}` — the index and alerts when the task
  starts (`["*"]` = a whole catalog table); papers in `saved_paper_ids` start in the library.
  Alerts keep their catalogued read state. Baselines are measured right after it.
- `new_paper {paper_id}` (and its original twin `inject_target_paper`) — a paper is indexed.
- `new_alert {alert_id}` — an alert arrives, unread.
- `withdraw_paper {paper_id}` — its authors withdraw a preprint (apps.kit.retractions): it leaves
  results, recommendations, profiles and the library; its page (an alert about it still links
  there) says it was withdrawn, as arXiv's does, and it can no longer be saved or cited.

Unlike the original (a KeyError that aborted the event), an id missing from the catalog is
skipped, as in every other environment; scenario validation names it to the author. A paper
already indexed is left as the user has it (no duplicate, no reset of saved/cited).
"""

from __future__ import annotations

import json
from collections.abc import Iterable

from apps.kit.arrivals import Delivery, arrival, event_types, preload
from apps.kit.counts import ShownCount
from apps.kit.deciding import opening
from apps.kit.environments import declare
from apps.kit.retractions import retraction, window
from apps.kit.state import with_changed
from apps.kit.streaming import read_at
from apps.kit.tables import KEY, Table, named, tables
from apps.microscholar import state as index
from apps.microscholar.catalog import catalog_alert, catalog_paper, coauthor_pairs
from apps.microscholar.state import ENVIRONMENT, PaperState, Scholar, empty_scholar
from events.registry import counted

# The original's metric names (eval_sql reads baseline_<name> from session_meta).
BASELINES = counted(
    {
        "target_paper_available": index.target_paper_available,
        "paper_count": index.paper_count,
        "saved_paper_count": index.saved_paper_count,
        "unread_alert_count": index.unread_alert_count,
    }
)

deliver_papers = Delivery("papers", catalog_paper, states="paper_states", fresh=PaperState)
# Preloaded alerts keep their catalogued read state; new ones arrive unread.
deliver_alerts = Delivery("alerts", catalog_alert, states="alert_read")


def shelve(scholar: Scholar, paper_ids: Iterable[str], at: float, *, preloaded: bool) -> Scholar:
    """The library at the start: the listed papers indexed so far are saved."""
    for paper_id in paper_ids:
        scholar = with_changed(scholar, "paper_states", paper_id, saved=True)
    return scholar


NEW_PAPER = arrival(
    "new_paper",
    "paper_id",
    "papers",
    deliver_papers,
    help="A paper is indexed: it shows in results, recommendations and profiles.",
)

EVENT_TYPES = event_types(
    preload(
        "preload_papers",
        {
            "paper_ids": ("papers", deliver_papers),
            "alert_ids": ("alerts", deliver_alerts),
            "saved_paper_ids": ("papers", shelve),
        },
        environment=ENVIRONMENT,
        descriptions={"saved_paper_ids": "papers already in the library"},
        help="Papers, alerts and the saved library at the start; baselines are measured after it.",
    ),
    NEW_PAPER,
    ("inject_target_paper", NEW_PAPER[1]),  # the original's duplicate of new_paper
    arrival("new_alert", "alert_id", "alerts", deliver_alerts, help="An alert arrives, unread."),
    retraction(
        "withdraw_paper",
        "paper_id",
        "papers",
        "papers",
        help="Its authors withdraw a preprint: it leaves results, profiles and the library; its "
        "page says it was withdrawn.",
    ),
)


# --- evaluation tables (the original's names and columns; citedBy is ours, as of `now`) ---------


materialize = tables(
    Table(
        "papers",
        read_at(lambda scholar: scholar.papers.values()),
        {
            **named("id TEXT PRIMARY KEY", "title TEXT", "authors TEXT", "year INTEGER"),
            "isTargetPaper INTEGER": "is_target",
            "taskType TEXT": "task_type",
            **named("snippet TEXT", "source TEXT"),
            "citedBy INTEGER": lambda paper: paper.cited_by(paper.now),  # as of `now`
            **window("indexed_at"),
        },
    ),
    Table.keyed(
        "paper_states",
        "paper_states",
        {"paper_id TEXT PRIMARY KEY": KEY, "isSaved INTEGER": "saved", "isCited INTEGER": "cited"},
    ),
    Table.items(
        "alerts",
        {
            **named("id TEXT PRIMARY KEY", "type TEXT", "title TEXT", "description TEXT"),
            "relatedPaperId TEXT": "related_paper_id",
        },
    ),
    Table.keyed(
        "alert_states",
        "alert_read",
        {"alert_id TEXT PRIMARY KEY": KEY, "isRead INTEGER": lambda row: row.value},
    ),
    Table(
        "coauthors",
        lambda scholar, now: coauthor_pairs(scholar.catalog),
        {
            "authorId1 TEXT": "one",
            "authorId2 TEXT": "two",
            "sharedPapers TEXT": lambda pair: json.dumps(list(pair.shared)),
        },
    ),
)


def not_cited_yet(scholar: Scholar, paper_id: str) -> bool:
    return index.is_listed(scholar, paper_id) and not scholar.is_cited(paper_id)


# The numbers shown in more than one place (apps.kit.counts): the top bar's library and alert
# badges on every page, and the library and alert pages' own headings.
SHOWN_COUNTS = (
    ShownCount(
        "library",
        lambda scholar, now: index.saved_paper_count(scholar),
        ("My library {n}", "My library · {n} articles?"),
    ),
    ShownCount(
        "unread alerts",
        lambda scholar, now: index.unread_alert_count(scholar),
        ("Alerts {n} unread", "{n} unread alerts?"),
    ),
)


IMPLICIT_ACTIONS = (
    # Opening the Cite dialog is what records a citation in the original (no confirmation).
    opening("cite", "paper_id", "cite", "paper_id", applies=not_cited_yet),
)


MICROSCHOLAR = declare(__name__, title="MicroScholar", initial_state=empty_scholar)
