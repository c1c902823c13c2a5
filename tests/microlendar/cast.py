"""The cast of the MicroLendar tests, from our catalog (fixtures/microlendar/events.jsonl).

Chris Taylor (the self user) opens the calendar on Thursday 18 September 2025. Preloaded: the
day's first four events (`td-01` standup 9:30, `td-02` grooming 10:00, `td-03` lunch with Rosa,
`td-04` interview), the overlapping pair `cf-01` / `cf-02` on Monday 22 September, the
"Metrics readout" `desc-analytics-1` (Friday 19th) and three tasks (`tk-03` already done).
`td-05` (coffee with Hana, 11:00 today) is added at t=60.
"""

from __future__ import annotations

from apps.microlendar.environment import MICROLENDAR
from apps.microlendar.state import Agenda
from events.catalog import load_catalog
from events.registry import LoggedEvent

TODAY = "2025-09-18"
PRELOADED = ["td-01", "td-02", "td-03", "td-04", "cf-01", "cf-02", "desc-analytics-1"]
TASKS = ["tk-01", "tk-02", "tk-03"]
LATE_EVENT, LATE_AT = "td-05", 60.0


def scenario() -> dict:
    return {
        "id": "test-microlendar-cast",
        "environment": "microlendar",
        "prompt": "Test cast.",
        "start_page": "HOST_ADDRESS/microlendar",
        "condition_at": LATE_AT,
        "event_timeline_end": 720.0,
        "kill_at": 630.0,
        "taxonomy": {},
        "events": [
            {
                "time": 0.0,
                "type": "preload_events",
                "payload": {
                    "today": TODAY,
                    "initial_date": TODAY,
                    "event_ids": PRELOADED,
                    "task_ids": TASKS,
                },
            },
            {"time": LATE_AT, "type": "new_event", "payload": {"event_id": LATE_EVENT}},
        ],
        "eval_sql": "SELECT 1",
    }


def scenario_event(type: str, payload: dict, *, at: float = 0.0, seq: int = 1) -> LoggedEvent:
    return LoggedEvent(seq, at, "scenario", type, payload)


def action(type: str, payload: dict, *, at: float = 1.0, seq: int = 2) -> LoggedEvent:
    return LoggedEvent(seq, at, "action", type, payload)


def preloaded() -> Agenda:
    """The cast's calendar right after the preload."""
    empty = MICROLENDAR.initial_state(load_catalog())
    return MICROLENDAR.apply(
        empty, scenario_event("preload_events", scenario()["events"][0]["payload"])
    )


def act(agenda: Agenda, name: str, payload: dict, *, at: float = 1.0) -> Agenda:
    """Decide and apply an agent action, as the core does (logged payload → reducer)."""
    logged = MICROLENDAR.actions[name].decide(agenda, dict(payload))
    return MICROLENDAR.apply(agenda, action(name, logged, at=at))
