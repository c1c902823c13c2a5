"""What an agent can do to the tally: `poke {n}` adds n (> 0) to it, from the Poke form."""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType

from apps.tally.state import TallyState, with_entry
from events.registry import Action, ActionRejected, LoggedEvent, PageStep
from events.schemas import Payload


class Count(Payload):
    n: int


def decide_poke(state: TallyState, payload: dict) -> dict:
    if payload["n"] <= 0:
        raise ActionRejected(f"n must be a positive integer, got {payload['n']}")
    return payload


def reduce_poke(state: TallyState, event: LoggedEvent) -> TallyState:
    return with_entry(state, "poke", event.payload["n"], event.at)


def poke_page(state: TallyState, payload: dict) -> PageStep:
    """The tally page's Poke form, with `n` typed in."""
    return PageStep("", {"n": str(payload["n"])})


ACTIONS: Mapping[str, Action] = MappingProxyType(
    {
        "poke": Action(
            Count, decide_poke, reduce_poke, help="Add n (> 0) to the tally.", page=poke_page
        ),
    }
)
