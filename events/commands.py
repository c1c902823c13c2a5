"""What agents do to a run: actions (logged as `action` events) and page views (`view`).

An action is validated against the *current* state (due entries are fired first, so the agent
never acts on a stale world), then logged; the environment's reducer applies it on the next
fold. A completed run still accepts actions, as upstream does, but grading ignores anything
after the first contact.
"""

from __future__ import annotations

from typing import Any

from events.clock import sim_now, wall_now
from events.models import Event, EventKind, Run
from events.notifications import log_grew
from events.projection import Folded, folded_state
from events.registry import ActionRejected, PayloadError, get_environment, validate_payload
from events.scheduler import fire_due
from events.store import append_event


def current_folded(run: Run, *, wall: float | None = None, reload: bool = True) -> Folded:
    """The state an agent sees at wall time `wall` (default: now), with its log position: fire
    what is due by then, then fold (zero staleness). `reload=False` when `run` was read from the
    database just now."""
    fire_due(run, wall=wall, reload=reload)
    return folded_state(run)


def current_state(run: Run) -> Any:
    return current_folded(run).state


def perform_action(
    run: Run, name: str, payload: dict[str, Any], *, wall: float | None = None
) -> Event:
    """Validate `payload`, decide against the state at `wall` (the operation's one clock
    reading; default now) and log the action at that same simulated time."""
    if run.closed_at is not None:
        raise ActionRejected("this run is closed", status=409)
    environment = get_environment(run.environment)
    action = environment.actions.get(name)
    if action is None:
        raise ActionRejected(
            f"unknown action {name!r} for {environment.name}; allowed: {', '.join(sorted(environment.actions))}",
            status=400,  # the request names no such thing: a bad request, not a missing page
        )
    try:
        validate_payload(action.schema, payload, what=f"action {name}")
    except PayloadError as exc:
        raise ActionRejected(str(exc)) from None
    wall = wall_now() if wall is None else wall
    state = current_folded(run, wall=wall).state
    at = sim_now(run, wall)
    recorded = action.decide_at(state, dict(payload), at)
    event = append_event(run, EventKind.ACTION, name, recorded, at=at)
    log_grew(run.pk, event.seq)  # other tabs of this run get pushed
    return event


def record_view(run: Run, path: str, *, at: float, **details: Any) -> Event:
    """Log a page view at simulated time `at` (cheap; used for replay and activity metrics)."""
    return append_event(run, EventKind.VIEW, "page", {"path": path, **details}, at=at)
