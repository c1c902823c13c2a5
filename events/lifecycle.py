"""Life-cycle of a run: create, start, advance, contact, complete, close.

Each transition is a conditional write (`UPDATE … WHERE status IN …`), so two processes can
never both perform it, and each is logged as a `lifecycle` event so a replay shows it.
Errors a caller can cause raise `LifecycleError` with the HTTP status and a clear message.
"""

from __future__ import annotations

import math
from typing import Any

from django.db import transaction
from django.utils import timezone

from events import notifications, projection, scheduler
from events.catalog import load_catalog
from events.clock import sim_now, wall_now
from events.commands import budget_spent, current_folded
from events.models import CONTACT_GET, CONTACT_POST, ClockMode, Event, EventKind, Run, RunStatus
from events.registry import get_environment
from events.scheduler import FireResult, fire_due
from events.store import append_event
from events.ticker import notify_clock_started
from events.timing import validate_speed_factor

CLOCK_STARTABLE = (RunStatus.READY, RunStatus.RUNNING_MANUAL)


class LifecycleError(Exception):
    def __init__(self, message: str, status: int = 409):
        super().__init__(message)
        self.status = status


def _log(run: Run, type: str, at: float, payload: dict[str, Any] | None = None) -> Event:
    return append_event(run, EventKind.LIFECYCLE, type, payload or {}, at=at)


def create_run(
    spec: dict[str, Any],
    *,
    speed_factor: float = 1.0,
    clock_mode: str = ClockMode.LIVE,
    default_slot: bool = False,
    catalog_dir=None,
) -> Run:
    """Create a run of the scenario `spec` (see Scenario.to_run_spec) and fire its preloads."""
    speed_factor = validate_speed_factor(speed_factor)
    if clock_mode not in ClockMode.values:
        raise LifecycleError(
            f"clock_mode {clock_mode!r} is not valid; allowed: {', '.join(ClockMode.values)}", 400
        )
    get_environment(spec["environment"])  # raises UnknownEnvironment listing the valid names
    catalog = load_catalog(catalog_dir)
    with transaction.atomic():
        run = Run.objects.create(
            scenario_id=spec["id"],
            environment=spec["environment"],
            scenario=spec,
            speed_factor=speed_factor,
            clock_mode=clock_mode,
            catalog_dir=str(catalog.directory),
            catalog_hash=catalog.content_hash,
            is_default_slot=default_slot,
        )
    run.remember_spec()  # the ticker, /status and the pages read it deferred
    _log(run, "init", 0.0, {"speed_factor": speed_factor, "clock_mode": clock_mode})
    # The t ≤ 0 preload, which also captures the baselines. The run was written just now and
    # nothing of its timeline has fired: no re-read, no search for the first unfired entry.
    fire_due(run, reload=False, next_index=0)
    return run


def start_clock(run: Run, *, wall: float | None = None) -> Run:
    """Start (or resume after manual advances) the live clock: → running_auto."""
    if run.clock_mode == ClockMode.VIRTUAL:
        raise LifecycleError("this run has a virtual clock: move it with advance")
    wall = wall_now() if wall is None else wall
    run.refresh_from_db()
    # Continue from where manual advances left the clock (upstream restarted from 0).
    started_at = wall - (run.sim_time - run.skipped) / run.speed_factor
    if not Run.objects.filter(pk=run.pk, status__in=CLOCK_STARTABLE, closed_at__isnull=True).update(
        status=RunStatus.RUNNING_AUTO, started_at=started_at
    ):
        run.refresh_from_db()
        raise LifecycleError(
            f"Wrong state: starting the clock requires 'ready' or 'running_manual'. Current: '{run.status}'."
        )
    run.refresh_from_db()
    _log(run, "start", run.sim_time, {"started_at": started_at})
    notify_clock_started(run)
    notifications.clock_moved(run.pk)
    return run


def require_virtual_clock(run: Run) -> None:
    """Refuse to move a clock that belongs to the wall: a live or fast-forward run graded on a
    clock its holder could jump would report any reaction time it liked (the control API's
    `/advance` asks this; tests and `bench_scale` position runs through `advance` itself)."""
    if run.clock_mode != ClockMode.VIRTUAL:
        raise LifecycleError(
            f"/advance moves only a virtual clock: run {run.pk} has a {run.clock_mode} clock, "
            "which moves with the wall (create the run with clock_mode 'virtual' to step it)"
        )


def advance(run: Run, to: float) -> FireResult:
    """Move a manual clock to simulated time `to` (authored seconds) and fire what is due."""
    run.refresh_from_db()
    if not math.isfinite(to) or to < 0:  # an infinite clock would break every read of the run
        raise LifecycleError(f"time must be a finite number ≥ 0, got {to}", 422)
    if run.status not in CLOCK_STARTABLE or run.closed_at is not None:
        raise LifecycleError(
            f"Wrong state: /advance requires 'ready' or 'running_manual'. Current: '{run.status}'."
        )
    if to < run.sim_time:
        raise LifecycleError(
            f"time cannot move backwards: the clock is at {run.sim_time:g} s, asked for {to:g} s",
            400,
        )
    if not Run.objects.filter(
        pk=run.pk, status__in=CLOCK_STARTABLE, sim_time__lte=to, closed_at__isnull=True
    ).update(status=RunStatus.RUNNING_MANUAL, sim_time=to):
        raise LifecycleError("the run changed concurrently; read its status and retry")
    _log(run, "advance", to)
    notifications.clock_moved(run.pk)
    return fire_due(run)


def complete(run: Run, *, wall: float | None = None) -> Run:
    """Freeze the clock at its value at wall time `wall` (default now: read once, so what is
    fired and where the clock stops are the same moment). Idempotent."""
    wall = wall_now() if wall is None else wall
    fire_due(run, wall=wall)
    if run.status != RunStatus.COMPLETED and not run.complete_at(sim_now(run, wall)):
        run.reread("status", "sim_time")  # another caller completed it first: its time holds
    return run


def contact(
    run: Run, *, method: str, message: str | None = None, wall: float | None = None
) -> Event:
    """The agent's "done / condition met" signal, at wall time `wall` (when the request arrived;
    default now). Completes the run; every visit is logged.

    A contact is the agent's entry in its run's log, counted in its budget as its actions are
    (events/commands.py): once that is spent, a contact is refused (429) and changes nothing."""
    if run.closed_at is not None:
        raise LifecycleError("No active simulation. Call /init first.")
    wall = wall_now() if wall is None else wall
    if spent := budget_spent(run, current_folded(run, wall=wall)):
        raise LifecycleError(spent, 429)
    complete(run, wall=wall)  # fires what was due first: the contact sees "now", not a tick ago
    if method == "POST":
        return _log(run, CONTACT_POST, run.sim_time, {"message": message or ""})
    return _log(run, CONTACT_GET, run.sim_time)


def close(run: Run) -> None:
    """Close the run, and forget what this process kept for it (its fold, its scenario): a
    server that has served a thousand runs holds what one that served ten holds."""
    run.close_once(timezone.now())
    _log(run, "close", run.sim_time)
    projection.forget(run)
    scheduler.forget(run)
    run.forget_spec()
    notifications.run_closed(run.pk)


def status_snapshot(run: Run, *, reload: bool = True) -> dict[str, Any]:
    """Current status, firing what is due first (zero staleness). `reload=False` for a caller
    that has just read or written the run (the flat endpoints): reading it again would only
    cost a query."""
    wall = wall_now()
    fire_due(run, wall=wall, reload=reload)
    now = sim_now(run, wall)
    return {"status": run.status, "sim_time": now, "next_event_time": _next_event_time(run, now)}


def _next_event_time(run: Run, now: float) -> float | None:
    if run.status == RunStatus.COMPLETED:
        return None
    end = run.event_timeline_end  # read once: every read goes through the run's spec
    return next((e["time"] for e in run.timeline if now < e["time"] <= end), None)
