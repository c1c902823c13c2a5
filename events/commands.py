"""What agents do to a run: actions (logged as `action` events) and page views (`view`).

An action is validated against the *current* state (due entries are fired first, so the agent
never acts on a stale world), then logged; the environment's reducer applies it on the next
fold. A completed run still accepts actions, as upstream does, but grading ignores anything
after the first contact.
"""

from __future__ import annotations

from typing import Any, NamedTuple

from django.conf import settings

from events.clock import sim_now, wall_now
from events.models import Event, EventKind, Run
from events.notifications import log_grew
from events.projection import Folded, folded_after, folded_state
from events.registry import ActionRejected, get_environment
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


class Acted(NamedTuple):
    """An action logged: its event, and the run's state with it applied."""

    event: Event
    folded: Folded


def perform_action(
    run: Run,
    name: str,
    payload: dict[str, Any],
    *,
    wall: float | None = None,
    folded: Folded | None = None,
) -> Acted:
    """Validate `payload`, decide against the state at `wall` (the operation's one clock
    reading; default now) and log the action at that same simulated time.

    `folded` is the state the caller already brought up to `wall` (a page request fired what
    was due and folded once on arrival): the action is decided on it, and the new state is that
    state with the one logged event applied — no second firing, no refold. Without it, what is
    due is fired and the log folded first."""
    if run.closed_at is not None:
        raise ActionRejected("this run is closed", status=409)
    environment = get_environment(run.environment)
    wall = wall_now() if wall is None else wall
    if folded is None:
        folded = current_folded(run, wall=wall)
    if spent := budget_spent(run, folded):
        raise ActionRejected(spent, status=429)
    at = sim_now(run, wall)
    performed = environment.perform(folded.state, name, payload, at)
    event = append_event(run, EventKind.ACTION, name, performed.payload, at=at)
    log_grew(run.pk, event.seq)  # other tabs of this run get pushed
    return Acted(event, folded_after(run, folded, event, performed.state))


# A viewed URL is kept to this many characters. The agent chooses its URLs, and a query string
# of 15 KB on every GET grew its own run's log (and every export and replay of it) without bound.
VIEW_PATH_LIMIT = 2048


def budget_spent(run: Run, folded: Folded) -> str | None:
    """Why the agent may add nothing more to the run's log (None: it may). Its actions, page
    views and contacts are bounded in number and in stored bytes, over and above the scenario's
    own timeline: an agent looping on one request, or posting maximal texts, grew its run's log,
    its exports and replays without bound."""
    entries = settings.SENTINEL_AGENT_LOG_BUDGET
    if folded.seq >= len(run.timeline) + entries:
        return (
            f"this run's log is full: its agent has used its {entries:,} entries "
            f"({AGENT_ENTRIES}; SENTINEL_AGENT_LOG_BUDGET)"
        )
    stored = settings.SENTINEL_AGENT_BYTES_BUDGET
    if folded.agent_bytes >= stored:
        return (
            f"this run's log is full: its agent has stored {folded.agent_bytes:,} of its "
            f"{stored:,} bytes ({AGENT_ENTRIES}; SENTINEL_AGENT_BYTES_BUDGET)"
        )
    return None


AGENT_ENTRIES = "actions, page views and contacts"  # what the budget counts (projection.by_agent)


def has_room(run: Run, folded: Folded) -> bool:
    """Whether the agent may add to the run's log (see `budget_spent`)."""
    return budget_spent(run, folded) is None


def record_view(run: Run, path: str, *, at: float, **details: Any) -> Event:
    """Log a page view at simulated time `at` (cheap; used for replay and activity metrics).
    A path longer than VIEW_PATH_LIMIT is cut there; the entry says how long it was."""
    if len(path) > VIEW_PATH_LIMIT:
        details = {**details, "path_length": len(path)}
        path = path[:VIEW_PATH_LIMIT]
    return append_event(run, EventKind.VIEW, "page", {"path": path, **details}, at=at)
