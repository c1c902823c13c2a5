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
from apps.micromail.state import Mail
from apps.scenarios.format import parse_scenario
from events.catalog import load_catalog
from events.registry import ActionRejected, LoggedEvent, PayloadError, validate_payload

CATALOG_DIR = Path(__file__).resolve().parent / "catalog"

SELF_EMAIL = "robin.vale@micromail.test"
PRIYA = "priya.nair@micromail.test"
OMAR = "omar.haddad@micromail.test"
DANA = "dana@vendorco.example"

PRELOADED = ["budget-review", "team-lunch", "prize-scam", "vendor-quote", "old-archive"]
LATE_AT = 120.0


def catalog():
    return load_catalog(CATALOG_DIR)


def scenario_event(type: str, payload: dict, *, at: float = 0.0, seq: int = 1) -> LoggedEvent:
    return LoggedEvent(seq, at, "scenario", type, payload)


def fresh_mail() -> Mail:
    return MICROMAIL.initial_state(catalog())


def preloaded_mail(ids: list[str] | None = None) -> Mail:
    """The mailbox right after the t=0 preload of the cast (without late-report)."""
    return MICROMAIL.apply(
        fresh_mail(), scenario_event("preload_emails", {"email_ids": ids or PRELOADED})
    )


def act(mail: Mail, name: str, payload: dict, *, at: float = 10.0, seq: int = 100) -> Mail:
    """Validate, decide and apply one agent action, as the core does (without a database)."""
    action = MICROMAIL.actions[name]
    try:
        validate_payload(action.schema, payload, what=f"action {name}")
    except PayloadError as exc:
        raise ActionRejected(str(exc)) from None
    recorded = action.decide(mail, dict(payload))
    return MICROMAIL.apply(mail, LoggedEvent(seq, at, "action", name, recorded))


def mailbox_scenario(**overrides) -> dict:
    """A scenario over the cast: preload at 0, late-report at 120 (the condition)."""
    data = {
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
    }
    data.update(overrides)
    return parse_scenario(data, source="tests/micromail").to_run_spec()
