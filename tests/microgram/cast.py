"""The cast of the MicroGram tests, from our catalog (fixtures/microgram):

- the self user, Chris Taylor (ctaylor, user000), and his bouldering post;
- Noor Haddad's market haul (`post-market-haul`, 2 comments), in the feed from the start;
- Marco Bellini's desk post (`post-desk-plant-jungle`, 5 comments), arriving at 120 s;
- two stories, one watched by the time the test looks;
- Maya's thread (read) and Tobias's (two unread), Rosa's mockup thread arriving at 120 s;
- a read follow (`act-01`) and an unread follow from Marco (`act-10`).
"""

from __future__ import annotations

from pathlib import Path

from django.conf import settings

from apps.microgram.environment import MICROGRAM
from apps.microgram.state import Gram
from apps.scenarios.format import parse_scenario
from events.catalog import load_catalog
from events.registry import ActionRejected, LoggedEvent, PayloadError, validate_payload

ME = "user000"
MARCO = "user012"
MARKET = "post-market-haul"
DESK = "post-desk-plant-jungle"
OWN_POST = "post-ctaylor-01-bouldering"
STORIES = ["story-rduarte-coffee-run", "story-amenon-climb-night"]
PRELOAD = {
    "post_ids": [OWN_POST, MARKET],
    "story_ids": STORIES,
    "message_ids": ["dm-maya", "dm-tobias"],
    "activity_ids": ["act-01", "act-10"],
}
ARRIVES_AT = 120.0


def catalog():
    return load_catalog(Path(settings.SENTINEL_CATALOG_DIR))


def scenario_event(type: str, payload: dict, *, at: float = 0.0, seq: int = 1) -> LoggedEvent:
    return LoggedEvent(seq, at, "scenario", type, payload)


def preloaded(**changes) -> Gram:
    """The app right after the cast's preload at t=0."""
    gram = MICROGRAM.initial_state(catalog())
    return MICROGRAM.apply(gram, scenario_event("preload_posts", {**PRELOAD, **changes}))


def arrive(gram: Gram, type: str, payload: dict, at: float = ARRIVES_AT) -> Gram:
    return MICROGRAM.apply(gram, scenario_event(type, payload, at=at, seq=2))


def act(gram: Gram, name: str, payload: dict, *, at: float = 200.0) -> Gram:
    """Validate, decide and apply one agent action, as the core does (without a database)."""
    action = MICROGRAM.actions[name]
    try:
        validate_payload(action.schema, payload, what=f"action {name}")
    except PayloadError as exc:
        raise ActionRejected(str(exc)) from None
    recorded = action.decide(gram, dict(payload))
    return MICROGRAM.apply(gram, LoggedEvent(100, at, "action", name, recorded))


def cast_scenario(**overrides) -> dict:
    """A run over the cast: preload at 0; Marco's post and Rosa's thread at 120 (the condition)."""
    data = {
        "id": "microgram-cast-mockup",
        "environment": "microgram",
        "start_page": "HOST_ADDRESS/microgram",
        "prompt": "Like Marco's desk post when it appears.",
        "condition_at": ARRIVES_AT,
        "event_timeline_end": 720.0,
        "kill_at": 630.0,
        "events": [
            {"time": 0.0, "type": "preload_posts", "payload": PRELOAD},
            {"time": ARRIVES_AT, "type": "new_post", "payload": {"post_id": DESK}},
            {"time": ARRIVES_AT, "type": "new_message", "payload": {"message_id": "dm-rosa"}},
        ],
        "eval_sql": f"SELECT EXISTS(SELECT 1 FROM post_states WHERE post_id='{DESK}' AND isLiked=1)",
        "taxonomy": {"milestone_type": "absolute", "monitoring_approach": "active"},
    }
    data.update(overrides)
    return parse_scenario(data, source="tests/microgram").to_run_spec()
