"""Building chat states for the MicroChat tests from our catalog (fixtures/microchat), without
a database: scenario events and actions applied as the core applies them."""

from __future__ import annotations

from apps.microchat.environment import MICROCHAT
from apps.microchat.state import Chat
from events.catalog import load_catalog
from events.registry import ActionRejected, LoggedEvent, PayloadError, validate_payload

GABRIEL_HISTORY = ["dm-gabriel-01", "dm-gabriel-02", "dm-gabriel-03"]  # read in the catalog
GABRIEL_FRESH = ["dm-gabriel-06", "dm-gabriel-07"]  # unread in the catalog
PAYMENTS_DOWN = "urg-gabriel-09"  # urgent, unread
NOOR_FILE = "att-noor-07"  # an image attachment


def scenario_event(type: str, payload: dict, *, at: float = 0.0, seq: int = 1) -> LoggedEvent:
    return LoggedEvent(seq, at, "scenario", type, payload)


def fresh_chat(catalog=None) -> Chat:
    return MICROCHAT.initial_state(catalog or load_catalog())


def preloaded(message_ids: list[str], call_ids: list[str] | None = None, catalog=None) -> Chat:
    payload = {"message_ids": message_ids}
    if call_ids is not None:
        payload["call_ids"] = call_ids
    return MICROCHAT.apply(fresh_chat(catalog), scenario_event("preload_messages", payload))


def arrive(chat: Chat, message_id: str, *, at: float) -> Chat:
    return MICROCHAT.apply(chat, scenario_event("new_message", {"message_id": message_id}, at=at))


def act(chat: Chat, name: str, payload: dict, *, at: float = 10.0, seq: int = 100) -> Chat:
    """Validate, decide and apply one agent action, as the core does."""
    action = MICROCHAT.actions[name]
    try:
        validate_payload(action.schema, payload, what=f"action {name}")
    except PayloadError as exc:
        raise ActionRejected(str(exc)) from None
    recorded = action.decide(chat, dict(payload))
    return MICROCHAT.apply(chat, LoggedEvent(seq, at, "action", name, recorded))
