"""Building MicroFy states for the tests from our catalog (fixtures/microfy), without a
database: scenario events and actions applied as the core applies them."""

from __future__ import annotations

from apps.microfy.environment import MICROFY
from apps.microfy.state import Music
from events.catalog import load_catalog
from events.registry import ActionRejected, LoggedEvent, validate_payload


def scenario_event(type: str, payload: dict, *, at: float = 0.0, seq: int = 1) -> LoggedEvent:
    return LoggedEvent(seq, at, "scenario", type, payload)


def fresh(catalog=None) -> Music:
    return MICROFY.initial_state(catalog or load_catalog())


def preloaded(track_ids: list[str], **more) -> Music:
    payload = {"track_ids": track_ids, **more}
    return MICROFY.apply(fresh(), scenario_event("preload_tracks", payload))


def arrive(music: Music, track_id: str, *, at: float) -> Music:
    return MICROFY.apply(music, scenario_event("new_track", {"track_id": track_id}, at=at))


def act(music: Music, name: str, payload: dict, *, at: float = 10.0, seq: int = 100) -> Music:
    """Validate, decide and apply one agent action, as the core does."""
    action = MICROFY.actions[name]
    validate_payload(action.schema, payload, what=f"action {name}")
    decided = action.decide(music, payload)
    return MICROFY.apply(music, LoggedEvent(seq, at, "action", name, decided))


__all__ = ["ActionRejected", "act", "arrive", "fresh", "preloaded", "scenario_event"]
