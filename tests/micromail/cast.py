"""The cast of the MicroMail tests: a small named catalog and a scenario around it.

- the self user, Robin Vale, whose mailbox the agent drives;
- colleagues Priya Nair and Omar Haddad; an outsider, Dana Okafor (vendor);
- `budget-review` (Priya, high importance, mentions Robin, two attachments, unread),
  `team-lunch` (already read), `prize-scam` (junk, unknown sender), `vendor-quote` (external,
  Robin on cc), `old-archive` (archived, read) — all preloaded at t=0;
- `late-report` (Omar, "platform scalability", one attachment) arriving at t=120.
"""

from __future__ import annotations

from pathlib import Path

from apps.micromail.environment import MICROMAIL
from tests.kit import Cast

CATALOG_DIR = Path(__file__).resolve().parent / "catalog"

SELF_EMAIL = "robin.vale@micromail.test"
PRIYA = "priya.nair@micromail.test"
OMAR = "omar.haddad@micromail.test"
DANA = "dana@vendorco.example"

PRELOADED = ["budget-review", "team-lunch", "prize-scam", "vendor-quote", "old-archive"]
LATE_AT = 120.0

CAST = Cast(
    MICROMAIL,
    CATALOG_DIR,
    preload=("preload_emails", {"email_ids": PRELOADED}),
    # Preload at 0, late-report at 120 (the condition).
    scenario={
        "id": "micromail-cast-late-report",
        "environment": "micromail",
        "start_page": "HOST_ADDRESS/micromail",
        "prompt": "Tell me when Omar's report arrives.",
        "condition_at": LATE_AT,
        "event_timeline_end": 720.0,
        "kill_at": 630.0,
        "events": [
            {"time": 0.0, "type": "preload_emails", "payload": {"email_ids": PRELOADED}},
            {"time": LATE_AT, "type": "new_email", "payload": {"email_id": "late-report"}},
        ],
        "eval_sql": "SELECT EXISTS(SELECT 1 FROM emails WHERE id = 'late-report')",
        "taxonomy": {"milestone_type": "absolute", "monitoring_approach": "passive"},
    },
    acts_at=10.0,
    arrives_at=LATE_AT,
)


def inbox_scenario(scenario_id: str, prompt: str, preloaded: list[str], *later: dict) -> dict:
    """A MicroMail scenario on our own catalog with no condition: `preloaded` at t=0, then any
    `later` timeline entries (`{"time", "type", "payload"}`) — the browser tests' inboxes."""
    return {
        "id": scenario_id,
        "environment": "micromail",
        "prompt": prompt,
        "start_page": "HOST_ADDRESS/micromail",
        "condition_at": None,
        "event_timeline_end": 600.0,
        "kill_at": 600.0,
        "taxonomy": {},
        "events": [
            {"time": 0.0, "type": "preload_emails", "payload": {"email_ids": preloaded}},
            *later,
        ],
    }
