"""Proofs a generated scenario must pass before it is written.

The same proofs as `bench validate` and the admin's dry run, played in memory so a thousand
candidates take minutes, not hours:

- the dry run (apps.scenarios.dry_run): a passive condition first holds at `condition_at`
  (±1 s), an active one not before it without an action, a no-op's never; the solution performed
  at `condition_at` makes it hold; the watched page's text changes at `condition_at`
  (apps.scenarios.watching);
- the control agents of `bench validate` (apps.bench.agents), each played as it plays on a
  virtual clock at speed factor 4 — same moments (the oracle's margin after the condition, the
  sleeper's and act_all's before the deadline, fixed_time's 300 s), same actions (act_all's
  expanded by apps.bench.everything), graded by the server's rule (events.evaluation.grade: as of
  the first contact, failed when earlier than the condition; a no-op passes without contact, and
  only for an agent still there at the end) — and judged by the same rules: the oracle passes,
  early and never fail a targeted task, never passes a no-op, and apps.bench's
  `cheating_problems` (act_all and fixed_time pass no active task and no no-op, quitter nothing);
  and on an ephemeral scenario the late agent (the oracle's solution, skipping what is refused,
  the margin after `condition_until`) fails.

`bench validate --scenarios DIR` on the written folder replays them through the real harness
and server (tests/scenarios/test_generation.py does so on a small folder).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from apps.bench.agents import CONDITION_MARGIN_S, FIXED_CONTACT_AT, SLEEPER_MARGIN_S
from apps.bench.cheating import cheating_problems
from apps.bench.everything import every_item_steps
from apps.bench.runner import deadline_s
from apps.generate.compose import waypoint_lists
from apps.scenarios.dry_run import TOLERANCE_S, dry_run
from apps.scenarios.format import ScenarioError
from apps.scenarios.serialization import render_json, scenario_file_of
from events.catalog import load_catalog
from events.evaluation import GradingSnapshot
from events.registry import (
    EMPTY,
    ActionRejected,
    LoggedEvent,
    PayloadError,
    get_environment,
    validate_payload,
)
from events.sandbox import is_truthy, run_eval_sql
from events.timing import REACTION_WINDOW

SPEED_FACTOR = 4.0  # bench validate's default, the README's
AGENTS = ("oracle", "early", "never", "sleeper", "act_all", "fixed_time", "quitter", "late")


@dataclass(frozen=True)
class Proof:
    verdicts: dict[str, bool] = field(default_factory=dict)  # control agent -> passed
    reports: dict[str, float | None] = field(default_factory=dict)  # -> when it reported
    problems: tuple[str, ...] = ()  # why the scenario is discarded; () when it is kept
    watch: str = ""  # the watched-page check's line (targeted scenarios)

    @property
    def ok(self) -> bool:
        return not self.problems


class _Play:
    """A scenario played in memory on a virtual clock, as the harness's runs are."""

    def __init__(self, spec: dict[str, Any]):
        self.spec = spec
        self.environment = get_environment(spec["environment"])
        self.end = float(spec["event_timeline_end"])
        self.condition = spec.get("condition_at")
        self.until = spec.get("condition_until")  # an ephemeral condition's end
        self.sql = (spec.get("eval_sql") or "").strip()
        self.deadline = deadline_s(spec, SPEED_FACTOR, REACTION_WINDOW)
        fired = sorted(
            (e for e in spec["events"] if float(e["time"]) <= self.end),
            key=lambda e: float(e["time"]),
        )
        self.events = [
            LoggedEvent(seq, float(e["time"]), "scenario", e["type"], e.get("payload") or {})
            for seq, e in enumerate(fired, 1)
        ]

    def first_holds(self, moments: list[float]) -> float | None:
        """The first of `moments` (sorted) at which eval_sql holds with no agent action,
        folding the timeline once."""
        env = self.environment
        state, baselines = env.initial_state(load_catalog()), EMPTY
        pending = list(self.events)
        for at in moments:
            due = [e for e in pending if e.at <= at]
            pending = pending[len(due) :]
            state, baselines = env.fold(state, due, baselines)
            snapshot = GradingSnapshot(env, state, baselines, at, SPEED_FACTOR, self.end)
            outcome = run_eval_sql(self.sql, snapshot.write)
            if outcome.ok and is_truthy(outcome.value):
                return at
        return None

    def passive_problem(self) -> str:
        """A passive condition must not hold before condition_at — checked at every timeline
        entry before it (a distractor arriving even a moment before the trigger that meets the
        condition is caught), every waypoint (a value moving between waypoints is extreme at
        one) and TOLERANCE_S before it — and must hold by TOLERANCE_S after it (a crossing
        between waypoints). The dry run samples entries only, with ±TOLERANCE_S either side."""
        condition = float(self.condition)
        early = condition - TOLERANCE_S
        moments = {e.at for e in self.events if e.at < condition}
        for event in self.spec["events"]:
            for points in waypoint_lists(event):
                moments |= {float(t) for t, _ in points if float(t) < early}
        moments |= {max(0.0, early), condition, condition + TOLERANCE_S}
        first = self.first_holds(sorted(moments))
        if first is None:
            return f"passive task: the condition does not hold by condition_at {condition:g} s"
        if first < condition and (first != early or self._entry_at(first)):
            return (
                f"passive task: the condition holds at {first:g} s, "
                f"before condition_at {condition:g} s"
            )
        return ""

    def _entry_at(self, at: float) -> bool:
        return any(e.at == at for e in self.events)

    def holds(self, at: float, steps: list[dict], *, skip_refused: bool) -> bool:
        """eval_sql as of `at` after the timeline up to `at` and the agent's `steps` then."""
        env = self.environment
        state, baselines = env.fold(
            env.initial_state(load_catalog()), [e for e in self.events if e.at <= at], EMPTY
        )
        for i, step in enumerate(steps):
            action = env.actions.get(step.get("action"))
            try:
                if action is None:
                    raise ActionRejected(f"unknown action {step.get('action')!r}")
                payload = dict(step.get("payload") or {})
                validate_payload(action.schema, payload, what=step["action"])
                recorded = action.decide_at(state, payload, at)
            except (ActionRejected, PayloadError):
                if skip_refused:
                    continue
                return False
            event = LoggedEvent(100_000 + i, at, "action", step["action"], recorded)
            state = env.apply(state, event)
        if not self.sql:
            return False
        snapshot = GradingSnapshot(env, state, baselines, at, SPEED_FACTOR, self.end)
        outcome = run_eval_sql(self.sql, snapshot.write)
        return outcome.ok and is_truthy(outcome.value)

    def contact(self, at: float, steps: list[dict] = (), *, skip_refused: bool = False) -> bool:
        """The verdict of an agent that acts then reports at simulated `at`."""
        if self.condition is None or at < float(self.condition):
            return False  # a no-op contacted; a report before the condition
        return self.holds(at, list(steps), skip_refused=skip_refused)

    def stays(self, *, alive: bool) -> bool:
        """The verdict of an agent that never reports (alive: still there at the end)."""
        if self.condition is not None or not alive:
            return False
        return not self.sql or self.holds(self.end, [], skip_refused=False)

    def reports(self) -> dict[str, float | None]:
        """The simulated moment each control agent reports at (None: never), as it plays on a
        virtual clock: the oracle its margin after the condition, the sleeper and act_all theirs
        before the deadline, fixed_time at 300 s when the run lasts that long."""
        deadline = self.deadline * SPEED_FACTOR
        last = deadline - SLEEPER_MARGIN_S * SPEED_FACTOR
        condition, margin = self.condition, CONDITION_MARGIN_S * SPEED_FACTOR
        return {
            "oracle": None if condition is None else float(condition) + margin,
            "early": 0.0,
            "never": None,
            "sleeper": last,
            "act_all": min(last, self.end),
            "fixed_time": FIXED_CONTACT_AT if deadline > FIXED_CONTACT_AT else None,
            "quitter": None,
            "late": None
            if condition is None
            else float(condition if self.until is None else self.until) + margin,
        }

    def verdicts(self) -> dict[str, bool]:
        at = self.reports()
        solution = list(self.spec.get("solution") or [])
        act_all = at["act_all"]
        return {
            "oracle": self.stays(alive=True)
            if at["oracle"] is None
            else self.contact(at["oracle"], solution),
            "early": self.contact(at["early"]),
            "never": self.stays(alive=True),
            "sleeper": self.contact(at["sleeper"]),
            "act_all": self.contact(
                act_all, every_item_steps(self.spec, act_all), skip_refused=True
            ),
            "fixed_time": self.stays(alive=True)
            if at["fixed_time"] is None
            else self.contact(at["fixed_time"]),
            "quitter": self.stays(alive=False),
            "late": self.stays(alive=True)
            if at["late"] is None
            else self.contact(at["late"], solution, skip_refused=True),
        }


def control_problems(
    verdicts: dict[str, bool], *, noop: bool, active: bool, ephemeral: bool = False
) -> list[str]:
    """What `bench validate` reports as a PROBLEM for these verdicts of one scenario."""
    problems = [] if verdicts["oracle"] else ["oracle failed"]
    if ephemeral and verdicts["late"]:
        problems.append("late passed (acting after the window closed)")
    if not noop and verdicts["early"]:
        problems.append("early passed (trivially passable)")
    if verdicts["never"] != noop:
        problems.append(f"never {'failed' if noop else 'passed'}")
    ids, noops = ["it"], {"it"} if noop else set()
    problems += cheating_problems(
        lambda agent, _: verdicts[agent], ids, noops, ["it"] if active else [], "paper"
    )
    return [p.replace(" it", "") for p in problems]


def prove(document: dict[str, Any], proven: dict[str, Any] | None = None) -> Proof:
    """Every proof for the scenario `document` (as it would be written); `proven`, when given,
    is what the dry run plays instead (a withheld no-op's template eval_sql)."""
    source = f"{document['environment']}/{document['id']}.json"
    try:
        scenario_file_of(document, render_json(document), source, source=source)
        dry = scenario_file_of(
            proven or document, render_json(proven or document), source, source=source
        )
    except ScenarioError as error:
        return Proof(problems=(f"invalid: {error}",))
    checked = dry_run(dry.row, dry.events)
    play = _Play(document)
    passive = play.condition is not None and not _is_active(document)
    # A passive condition's timing is checked here, precisely (see _Play.passive_problem).
    problems = [
        f"dry run: {w}" for w in checked.warnings if not (passive and w.startswith("passive task:"))
    ]
    if passive and play.sql:
        problems += [p for p in [play.passive_problem()] if p]
    watch = next((n for n in checked.notes + checked.warnings if "watched page" in n), "")
    verdicts = play.verdicts()
    problems += control_problems(
        verdicts,
        noop=play.condition is None,
        active=_is_active(document),
        ephemeral=play.until is not None,
    )
    return Proof(verdicts, play.reports(), tuple(problems), watch)


def _is_active(document: dict[str, Any]) -> bool:
    return (document.get("taxonomy") or {}).get("monitoring_approach") == "active"
