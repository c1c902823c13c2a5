"""Building MicroScholar states from our catalog (fixtures/microscholar) without a database:
scenario events and actions applied as the core applies them."""

from __future__ import annotations

from apps.microscholar.environment import MICROSCHOLAR
from apps.microscholar.state import Scholar
from events.catalog import load_catalog
from events.registry import ActionRejected, LoggedEvent, PayloadError, validate_payload

BATCHING = "paper-001"  # "Batching Mobile Notifications…", C Taylor et al., CHI 2019, 214 citations
TARGET = "paper-041"  # "Deliberate Delegation…", the target paper
FORESTS = "paper-048"  # robotics, mentions unstructured environments


def scenario_event(type: str, payload: dict, *, at: float = 0.0, seq: int = 1) -> LoggedEvent:
    return LoggedEvent(seq, at, "scenario", type, payload)


def fresh() -> Scholar:
    return MICROSCHOLAR.initial_state(load_catalog())


def preloaded(paper_ids, alert_ids=(), saved=()) -> Scholar:
    payload = {
        "paper_ids": list(paper_ids),
        "alert_ids": list(alert_ids),
        "saved_paper_ids": list(saved),
    }
    return MICROSCHOLAR.apply(fresh(), scenario_event("preload_papers", payload))


def arrive(scholar: Scholar, paper_id: str, *, at: float) -> Scholar:
    return MICROSCHOLAR.apply(scholar, scenario_event("new_paper", {"paper_id": paper_id}, at=at))


def act(scholar: Scholar, name: str, payload: dict, *, at: float = 10.0, seq: int = 100) -> Scholar:
    action = MICROSCHOLAR.actions[name]
    try:
        validate_payload(action.schema, payload, what=f"action {name}")
    except PayloadError as exc:
        raise ActionRejected(str(exc)) from None
    recorded = action.decide(scholar, dict(payload))
    return MICROSCHOLAR.apply(scholar, LoggedEvent(seq, at, "action", name, recorded))
