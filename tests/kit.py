"""The test kit every environment's tests share: a cast (catalog + starting world + scenario)
and the pure core operations on it, with no database.

    CAST = Cast(MICROMAIL, CATALOG_DIR, preload=("preload_emails", {"email_ids": PRELOADED}),
                scenario={...}, acts_at=10.0, arrives_at=120.0)
    mail = CAST.preloaded()
    mail = CAST.arrive(mail, "new_email", {"email_id": "late-report"})
    mail = CAST.act(mail, "flag_email", {"email_id": "late-report"})   # Environment.perform

`act` is the server's own code path (`Environment.perform`: validate, decide, apply), so a test
of an action tests what an agent's request does, minus the database.
"""

from __future__ import annotations

import copy
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Generic, TypeVar

from apps.scenarios.format import parse_scenario
from events import lifecycle
from events.catalog import load_catalog
from events.models import ClockMode, Run
from events.registry import Environment, LoggedEvent

S = TypeVar("S")


def scenario_event(type: str, payload: Mapping[str, Any], *, at: float = 0.0, seq: int = 1):
    return LoggedEvent(seq, at, "scenario", type, payload)


def act(environment: Environment[S], state: S, name: str, payload: dict, *, at: float) -> S:
    """One agent action, validated, decided and applied as the server does (no database)."""
    return environment.perform(state, name, payload, at).state


@dataclass(frozen=True)
class Cast(Generic[S]):
    """A named little world for one environment's tests."""

    environment: Environment[S]
    catalog_dir: Path
    preload: tuple[str, Mapping[str, Any]]  # the t=0 preload: event type and payload
    scenario: Mapping[str, Any] = field(default_factory=dict)  # a scenario file's fields
    acts_at: float = 10.0  # when `act` happens unless told
    arrives_at: float = 120.0  # when `arrive` happens unless told

    def catalog(self):
        return load_catalog(self.catalog_dir)

    def fresh(self) -> S:
        return self.environment.initial_state(self.catalog())

    def preloaded(self, **changes: Any) -> S:
        """The world right after the cast's preload at t=0 (`changes` override its payload)."""
        type_, payload = self.preload
        return self.environment.apply(self.fresh(), scenario_event(type_, {**payload, **changes}))

    def arrive(self, state: S, type: str, payload: Mapping[str, Any], at: float | None = None):
        at = self.arrives_at if at is None else at
        return self.environment.apply(state, scenario_event(type, payload, at=at, seq=2))

    def act(self, state: S, name: str, payload: dict, *, at: float | None = None) -> S:
        return act(self.environment, state, name, payload, at=self.acts_at if at is None else at)

    def run_spec(self, **overrides: Any) -> dict:
        """The cast's scenario (fields overridden) as the core plays it."""
        data = {**copy.deepcopy(dict(self.scenario)), **overrides}
        return parse_scenario(data, source=f"tests/{self.environment.name}").to_run_spec()

    def start(self, **overrides: Any) -> Run:
        """A run of the cast's scenario on its catalog, preloaded, virtual clock at 0 (needs db)."""
        return lifecycle.create_run(
            self.run_spec(**overrides), clock_mode=ClockMode.VIRTUAL, catalog_dir=self.catalog_dir
        )
