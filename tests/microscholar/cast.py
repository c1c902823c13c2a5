"""The cast of the MicroScholar tests, from our catalog (fixtures/microscholar), without a
database: scenario events and actions applied as the core applies them (`tests.kit.Cast`).

The cast's scenario (its browser story): three papers indexed at the start, the target paper
"Deliberate Delegation" indexed at t=6; cite and save it. `CAST.act` happens at t=10 unless told.
"""

from __future__ import annotations

from pathlib import Path

from django.conf import settings

from apps.microscholar.environment import MICROSCHOLAR
from apps.microscholar.state import Scholar
from tests.kit import Cast

BATCHING = "paper-001"  # "Batching Mobile Notifications…", C Taylor et al., CHI 2019, 214 citations
TARGET = "paper-041"  # "Deliberate Delegation…", the target paper
FORESTS = "paper-048"  # robotics, mentions unstructured environments
TARGET_TITLE = "Deliberate Delegation: Language Agents for Multi-Step Office Workflows"
TARGET_AT = 6.0

CAST = Cast(
    MICROSCHOLAR,
    Path(settings.SENTINEL_CATALOG_DIR),
    preload=("preload_papers", {"paper_ids": [], "alert_ids": [], "saved_paper_ids": []}),
    scenario={
        "id": "browser-microscholar-cite",
        "environment": "microscholar",
        "prompt": "Cite and save the delegation paper when it is indexed.",
        "start_page": "HOST_ADDRESS/microscholar",
        "condition_at": TARGET_AT,
        "event_timeline_end": 600.0,
        "kill_at": 600.0,
        "taxonomy": {},
        "events": [
            {
                "time": 0.0,
                "type": "preload_papers",
                "payload": {"paper_ids": ["paper-021", "paper-022", "paper-023"], "alert_ids": []},
            },
            {"time": TARGET_AT, "type": "new_paper", "payload": {"paper_id": TARGET}},
        ],
        "eval_sql": f"""
SELECT (SELECT isCited FROM paper_states WHERE paper_id = '{TARGET}') = 1
  AND (SELECT isSaved FROM paper_states WHERE paper_id = '{TARGET}') = 1
  AND (SELECT COUNT(*) FROM paper_states WHERE isCited = 1 OR isSaved = 1) = 1
""",
    },
    acts_at=10.0,
)
act = CAST.act


def preloaded(paper_ids, alert_ids=(), saved=()) -> Scholar:
    """The index right after a preload of these papers, alerts and saved papers."""
    return CAST.preloaded(
        paper_ids=list(paper_ids), alert_ids=list(alert_ids), saved_paper_ids=list(saved)
    )
