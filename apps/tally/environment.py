"""`tally`: a test-only environment, installed by tests/settings.py (never in production).

It exists so the engine and the generic environment tests (tests/environments/) run end to end
on something far simpler than a real environment, while touching every part of the interface:

- scenario events `ping {n}` add to the tally; `preload {n, level_waypoints?}` is a ping the
  task starts with (the core measures the baselines right after it) and may lay out the level's
  waypoints `[[t, v], …]`; `level {value}` adds a level waypoint at the event's own time;
- the agent action `poke {n}` adds to the tally too, through the page's Poke form;
- the `level` moves between waypoints with the clock (a function of state and `now`);
- eval tables: `entries(source, n, at)` lists pings and pokes, `levels(value)` holds the level
  at `now`.
"""

from __future__ import annotations

from operator import itemgetter
from typing import Annotated

from pydantic import Field

from apps.kit.tables import Table, tables
from apps.tally.actions import ACTIONS, Count
from apps.tally.state import TallyState, with_entry, with_level_points
from events.registry import Environment, EventType, LoggedEvent, timeless
from events.schemas import Payload

__all__ = ["TALLY", "TallyState", "tally_scenario"]


class Preload(Count):
    level_waypoints: list[Annotated[list[float], Field(min_length=2, max_length=2)]] = Field(
        default_factory=list, description="[[time, value], …]: where the level goes, when"
    )


class Level(Payload):
    value: float


def reduce_ping(state: TallyState, event: LoggedEvent) -> TallyState:
    return with_entry(state, "ping", event.payload["n"], event.at)


def reduce_preload(state: TallyState, event: LoggedEvent) -> TallyState:
    """A ping, plus the level's waypoints (each by the waypoint insertion rule)."""
    state = reduce_ping(state, event)
    return with_level_points(state, event.payload.get("level_waypoints", ()))


def reduce_level(state: TallyState, event: LoggedEvent) -> TallyState:
    """A level waypoint at the event's own time: the level heads (or jumps) there."""
    return with_level_points(state, [(event.at, event.payload["value"])])


materialize = tables(
    Table(
        "entries",
        lambda state, now: state.entries,  # (source, n, at) tuples
        {"source TEXT": itemgetter(0), "n INTEGER": itemgetter(1), "at REAL": itemgetter(2)},
    ),
    Table("levels", lambda state, now: [state.level_at(now)], {"value REAL": float}),
)


TALLY = Environment(
    name="tally",
    title="Tally (test environment)",
    initial_state=lambda catalog: TallyState(),
    event_types={
        "preload": EventType(
            schema=Preload,
            reduce=reduce_preload,
            help="The tally the task starts with; baselines are measured after it.",
            preload=True,
        ),
        "ping": EventType(schema=Count, reduce=reduce_ping, help="Add n to the tally."),
        "level": EventType(
            schema=Level, reduce=reduce_level, help="A level waypoint at the event's time."
        ),
    },
    actions=ACTIONS,
    baselines={
        "total": timeless(lambda state: state.total),
        "pings": timeless(lambda state: len(state.entries)),
        "level": lambda state, now: state.level_at(now),
    },
    materialize=materialize,
    urlconf="apps.tally.urls",
)


def tally_scenario(
    *,
    condition_at: float | None = 30.0,
    pings: list[tuple[float, int]] | None = None,
    eval_sql: str | None = "SELECT (SELECT SUM(n) FROM entries WHERE source = 'ping') >= 3",
    scenario_id: str = "tally-three-absolute-passive",
) -> dict:
    """A scenario dict: by default one ping at t=0 (the preload), then two more; the tally
    reaches 3 at 30 s."""
    pings = pings if pings is not None else [(0.0, 1), (10.0, 1), (30.0, 1), (50.0, 5)]
    data = {
        "id": scenario_id,
        "environment": "tally",
        "start_page": "HOST_ADDRESS/tally",
        "prompt": "Tell me when the tally reaches 3.",
        "condition_at": condition_at,
        "event_timeline_end": 720.0,
        "kill_at": 630.0,
        "events": [
            {"time": t, "type": "preload" if t <= 0 else "ping", "payload": {"n": n}}
            for t, n in pings
        ],
        "annotator_notes": "",
        "taxonomy": {"milestone_type": "absolute", "monitoring_approach": "passive"},
    }
    if eval_sql is not None:
        data["eval_sql"] = eval_sql
    return data
