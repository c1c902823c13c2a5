"""Dry run: play a scenario's timeline with no agent and watch its eval_sql.

A throwaway fold in memory, nothing logged: the environment's initial state from the catalog,
each timeline entry applied as a `scenario` LoggedEvent, and after each one the eval_sql value
(with session_meta baselines, as grading computes them). Then the author's claims are checked:
a passive task's condition must first hold at `condition_at` (±1 s), a no-op's never; and a
task's watched page (`watch_page`, else the start page) must read differently at `condition_at`
than just before (apps.scenarios.watching).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from apps.scenarios.format import ScenarioError
from apps.scenarios.models import Scenario, TimelineEvent
from apps.scenarios.serialization import parsed_scenario, timeline_of
from apps.scenarios.watching import watch_check
from events.catalog import load_catalog
from events.evaluation import GradingSnapshot
from events.registry import (
    EMPTY,
    ActionRejected,
    LoggedEvent,
    PayloadError,
    UnknownEnvironment,
    get_environment,
    validate_payload,
)
from events.sandbox import is_truthy, run_eval_sql, shown

TOLERANCE_S = 1.0


@dataclass(frozen=True)
class Step:
    position: int
    time: float
    type: str
    value: Any
    holds: bool
    error: str
    baselines: dict[str, Any]
    fires: bool  # False for entries after event_timeline_end: they never fire


@dataclass
class DryRun:
    steps: list[Step] = field(default_factory=list)
    first_holds_at: float | None = None
    warnings: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    solution_holds: bool | None = None  # None: no solution to check

    @property
    def ok(self) -> bool:
        return not self.warnings


def dry_run(
    scenario: Scenario,
    events: list[TimelineEvent] | None = None,
    *,
    catalog_dir=None,
) -> DryRun:
    """Simulate `scenario` (optionally with an edited, unsaved timeline) and check it."""
    result = DryRun()
    if events is None:
        events = timeline_of(scenario)
    try:
        environment = get_environment(scenario.environment)
    except UnknownEnvironment as error:
        result.warnings.append(f"cannot simulate: {error}")
        return result
    state, baselines = environment.initial_state(load_catalog(catalog_dir)), EMPTY
    sql = (scenario.eval_sql or "").strip()
    end = scenario.event_timeline_end
    condition_at = scenario.condition_at
    at_condition = state, baselines  # as of condition_at, for the solution check
    for seq, entry in enumerate(sorted(events, key=lambda e: (e.time, e.position)), 1):
        fires = entry.time <= end
        if fires:
            event = LoggedEvent(seq, entry.time, "scenario", entry.type, entry.payload or {})
            state, baselines = environment.fold(state, [event], baselines)
            if condition_at is not None and entry.time <= condition_at:
                at_condition = state, baselines
        value, holds, error = None, False, ""
        if sql and fires:
            snapshot = _at(environment, state, baselines, entry.time, end)
            value, holds, error = _evaluate(snapshot, sql)
        if holds and result.first_holds_at is None:
            result.first_holds_at = entry.time
        result.steps.append(
            Step(
                entry.position, entry.time, entry.type, value, holds, error, dict(baselines), fires
            )
        )
    _check(scenario, result, sql)
    if condition_at is not None and not scenario.is_dev:
        _check_watched(scenario, events, result, catalog_dir)
    if sql and condition_at is not None and scenario.solution and not scenario.is_dev:
        _check_solution(scenario, environment, at_condition, sql, result)
    return result


def _at(environment, state, baselines, time: float, end: float) -> GradingSnapshot:
    """What grading at simulated time `time` would see (a dry run plays at speed 1)."""
    return GradingSnapshot(environment, state, baselines, time, 1.0, end)


def _evaluate(snapshot: GradingSnapshot, sql: str) -> tuple[Any, bool, str]:
    outcome = run_eval_sql(sql, snapshot.write)
    if not outcome.ok:
        return None, False, outcome.error
    return outcome.value, is_truthy(outcome.value), ""


def _check_solution(scenario: Scenario, environment, start, sql: str, result: DryRun) -> None:
    """The scenario's solution, performed at condition_at, must make the condition hold."""
    at = scenario.condition_at
    state, baselines = start
    for i, step in enumerate(scenario.solution):
        name, payload = step.get("action"), dict(step.get("payload") or {})
        action = environment.actions.get(name)
        if action is None:
            result.warnings.append(f"solution[{i}]: unknown action {name!r}")
            return
        try:
            validate_payload(action.schema, payload, what=f"solution[{i}] ({name})")
            recorded = action.decide_at(state, payload, at)
        except (PayloadError, ActionRejected) as error:
            result.warnings.append(
                f"solution[{i}] ({name}) is rejected at condition_at {at:g} s: {error}"
            )
            return
        state = environment.apply(state, LoggedEvent(10_000 + i, at, "action", name, recorded))
    snapshot = _at(environment, state, baselines, at, scenario.event_timeline_end)
    value, holds, error = _evaluate(snapshot, sql)
    result.solution_holds = holds
    if error:
        result.warnings.append(f"solution check: eval_sql failed: {error}")
    elif holds:
        result.notes.append(
            f"the solution performed at condition_at {at:g} s makes the condition hold"
        )
    else:
        result.warnings.append(
            f"the solution performed at condition_at {at:g} s does not make the condition hold "
            f"(eval_sql returned {shown(value)})"
        )


def _check_watched(scenario: Scenario, events, result: DryRun, catalog_dir) -> None:
    """Is the trigger there to be seen where the prompt says to watch?"""
    assert scenario.condition_at is not None
    try:  # the run's spec, as `bench validate` renders it: some pages read its timeline end
        spec = parsed_scenario(scenario, events).to_run_spec()
    except ScenarioError:  # an edited timeline not valid yet: render without it
        spec = None
    check = watch_check(
        scenario.environment,
        scenario.watch_page or scenario.start_page,
        scenario.condition_at,
        [
            {"time": e.time, "type": e.type, "payload": e.payload or {}}
            for e in sorted(events, key=lambda e: (e.time, e.position))
        ],
        scenario.event_timeline_end,
        spec=spec,
        catalog_dir=catalog_dir,
        source=scenario.path,
    )
    (result.notes if check.changes else result.warnings).append(check.detail)


def _check(scenario: Scenario, result: DryRun, sql: str) -> None:
    errors = sorted({s.error for s in result.steps if s.error})
    result.warnings.extend(f"eval_sql failed: {e}" for e in errors)
    if scenario.is_dev:
        result.notes.append("dev scenario: no condition to check")
        return
    first = result.first_holds_at
    if scenario.condition_at is None:
        if sql and first is not None:
            result.warnings.append(
                f"no-op task, but the condition holds without any agent action at {first:g} s"
            )
        elif not sql:
            result.notes.append("no-op without eval_sql: success only requires no contact")
        else:
            result.notes.append("no-op: the condition never holds, as it should")
        return
    approach = (scenario.taxonomy or {}).get("monitoring_approach")
    if approach == "passive":
        if first is None:
            result.warnings.append(
                f"passive task: the condition never holds, but condition_at is {scenario.condition_at:g} s"
            )
        elif abs(first - scenario.condition_at) > TOLERANCE_S:
            result.warnings.append(
                f"passive task: the condition first holds at {first:g} s, but condition_at is "
                f"{scenario.condition_at:g} s (off by {first - scenario.condition_at:+g} s)"
            )
        else:
            result.notes.append(
                f"passive task: the condition first holds at {first:g} s = condition_at"
            )
    else:
        if first is not None and first < scenario.condition_at - TOLERANCE_S:
            result.warnings.append(
                f"active task: the condition already holds at {first:g} s without any agent action, "
                f"before condition_at {scenario.condition_at:g} s"
            )
        else:
            result.notes.append(
                "active task: needs an agent action, so only checked that it does not hold early"
            )


def validate_timeline_entry(
    environment_name: str, type: str, payload: Any, *, catalog_dir=None
) -> list[str]:
    """Problems with one timeline entry: unknown type, payload schema, unknown catalog ids."""
    try:
        environment = get_environment(environment_name)
    except UnknownEnvironment:
        return []  # data-only environment: nothing to check against
    event_type = environment.event_types.get(type)
    if event_type is None:
        return [
            f"unknown event type {type!r}; allowed: {', '.join(sorted(environment.event_types))}"
        ]
    try:
        validate_payload(event_type.schema, payload, what=type)
    except PayloadError as error:
        return [str(error)]
    catalog = load_catalog(catalog_dir)
    problems = []
    for name, table in event_type.catalog_refs.items():
        if name not in payload:
            continue
        value = payload[name]
        ids = value if isinstance(value, list) else [value]
        missing = catalog.missing_ids(environment_name, table, [str(i) for i in ids])
        if missing:
            problems.append(f"{name}: not in catalog table {table!r}: {', '.join(missing)}")
    return problems
