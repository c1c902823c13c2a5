"""`tally`: a test-only environment (one event type, one action, one eval table).

It exists so the engine can be tested end to end without any real environment: scenario
events `ping {n}` add to a tally, the agent action `poke {n}` adds to it too, and the eval
table `entries(source, n, at)` lists both.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from events.registry import Action, Environment, EventType, LoggedEvent, timeless
from events.schemas import Payload
from events.tables import Table


class Count(Payload):
    n: int


@dataclass(frozen=True)
class TallyState:
    entries: tuple[tuple[str, int, float], ...] = ()

    @property
    def total(self) -> int:
        return sum(n for _, n, _ in self.entries)


def reduce_ping(state: TallyState, event: LoggedEvent) -> TallyState:
    return replace(state, entries=state.entries + (("ping", event.payload["n"], event.at),))


def reduce_poke(state: TallyState, event: LoggedEvent) -> TallyState:
    return replace(state, entries=state.entries + (("poke", event.payload["n"], event.at),))


def decide_poke(state: TallyState, payload: dict) -> dict:
    from events.registry import ActionRejected

    if payload["n"] <= 0:
        raise ActionRejected("n must be positive")
    return payload


ENTRIES = Table("entries", ("source TEXT", "n INTEGER", "at REAL"))


def materialize(state: TallyState, now: float, conn) -> None:
    ENTRIES.write(conn, state.entries)


TALLY = Environment(
    name="tally",
    title="Tally (test environment)",
    initial_state=lambda catalog: TallyState(),
    event_types={
        # A preload is a ping the task starts with: the core measures the baselines after it.
        "preload": EventType(schema=Count, reduce=reduce_ping, preload=True),
        "ping": EventType(schema=Count, reduce=reduce_ping),
    },
    actions={"poke": Action(schema=Count, decide=decide_poke, reduce=reduce_poke)},
    baselines={
        "total": timeless(lambda state: state.total),
        "pings": timeless(lambda state: len(state.entries)),
    },
    materialize=materialize,
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
