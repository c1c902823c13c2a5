"""Fast-forward: on a `fast_forward` run, a wait the agent declares skips the clock ahead.

The run's clock is a live clock (it runs at the speed factor while the agent works) plus
`skipped`, the sum of every skip (see events.clock for the one formula). A wait is one of

- `Wait(seconds=s)`: skip `s` simulated seconds, waking early at nothing (a sleep);
  `Wait(to=t)`: the same, up to simulated second `t` (an agent that keeps to moments of the
  run's clock lands on them exactly, though the clock ran on while its request travelled);
- `Wait(until_change=True, timeout=s)`: skip to the next scheduled timeline entry, at most `s`
  seconds, or at most up to second `to` (a wait for something to happen). With `since=t` the
  wait is for the first entry after simulated second `t` (the agent's last look): one that
  came while the agent was looking has happened already, so the wait answers at once instead
  of sleeping through it.

A skip never passes the run's kill_at (nor its timeline end). It moves the sum forward and, in
the same transaction, logs itself — a lifecycle `skip` event {from, to, why} at its `from` — and
fires every timeline entry it passed, in order, each at its own scheduled time, as the ticker
would have. The log therefore says everything: a replay refolds the same events, time travel
shows the skip where it happened, and other processes never see the new clock without the
entries it passed.

Concurrency: the clock moves by a conditional write on the sum it read (`skipped = seen`), so
two waits at once are applied one after the other (the loser reads again and skips from where
the winner left off), never both from the same moment; and a wait never starts before the last
skip ended, though its wall reading may be older than the one that skip was applied at. Entries
are fired by the same code as everything else, so the unique (run, timeline_index) keeps each
one once while the ticker or a page request fires too. An action posted meanwhile is appended
before or after the skip in the one log (its seq orders it), never lost.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from django.db import transaction

from events import notifications
from events.clock import CLOCK_FIELDS, sim_now, wall_due, wall_now
from events.lifecycle import CONTACT_GET, CONTACT_POST, LifecycleError
from events.models import ClockMode, Event, EventKind, Run, RunStatus
from events.scheduler import fire_due, fire_through
from events.store import append_event
from events.ticker import notify_clock_started

SKIP = "skip"  # the lifecycle event a skip logs
MAX_ATTEMPTS = 50

# Why a skip stopped where it did (the `why` of its log entry and of the answer).
SLEPT = "slept"  # a sleep ran its length
CHANGE = "change"  # the next scheduled entry came
TIMEOUT = "timeout"  # a wait for a change ran out first
KILL_AT = "kill_at"  # the run's last moment to skip to (kill_at or the timeline end)


class WaitRefused(LifecycleError):
    """A wait this run cannot take (wrong clock, not started, over); HTTP 409 by default."""


@dataclass(frozen=True)
class Wait:
    seconds: float | None = None
    until_change: bool = False
    timeout: float | None = None  # for until_change; None: as far as the run allows
    since: float | None = None  # for until_change: a change after this moment; None: after now
    to: float | None = None  # the simulated second it ends at, instead of seconds or timeout

    def __post_init__(self) -> None:
        if self.until_change:
            if self.seconds is not None:
                raise ValueError("a wait is either a sleep or until a change")
            if self.timeout is not None and self.to is not None:
                raise ValueError("a wait until a change ends after a timeout or at to, not both")
        else:
            if (self.seconds is None) == (self.to is None):
                raise ValueError("a sleep is either some seconds or up to a moment (to)")
            if self.since is not None or self.timeout is not None:
                raise ValueError("since and timeout go with a wait until a change")
        for name in ("seconds", "timeout", "since", "to"):
            value = getattr(self, name)
            if value is not None and not (math.isfinite(value) and value >= 0):
                raise ValueError(f"{name} must be a finite number of seconds ≥ 0, got {value!r}")

    def anchored(self, now: float) -> Wait:
        """This wait as asked at simulated second `now`, in moments instead of lengths: taken
        later (a server that paces its agents held it back), it ends where it would have."""
        if not self.until_change:
            return Wait(to=self.to if self.seconds is None else now + self.seconds)
        to = self.to if self.timeout is None else now + self.timeout
        return Wait(until_change=True, to=to, since=now if self.since is None else self.since)


@dataclass(frozen=True)
class Skipped:
    """What a wait did: the clock went from `start` to `end` (simulated seconds)."""

    start: float
    end: float
    why: str
    fired: list[Event] = field(default_factory=list)


def skip_limit(run: Run) -> float:
    """The last simulated second a wait may reach: kill_at, or the timeline end if sooner."""
    kill_at = run.spec.get("kill_at")
    end = run.event_timeline_end
    return end if kill_at is None else min(float(kill_at), end)


def target(run: Run, wait: Wait, now: float) -> tuple[float, str]:
    """Where a wait starting at `now` stops, and why (pure: the run's timeline and limit)."""
    limit = skip_limit(run)
    if not wait.until_change:
        end = now + wait.seconds if wait.seconds is not None else wait.to
        assert end is not None  # Wait's own check
        to, why = max(now, end), SLEPT
    else:
        after = now if wait.since is None else min(wait.since, now)
        upcoming = (entry["time"] for entry in run.timeline if entry["time"] > after)
        nxt = next(upcoming, math.inf)
        if wait.to is not None:
            horizon = max(now, wait.to)
        else:
            horizon = math.inf if wait.timeout is None else now + wait.timeout
        # A change after `since` that came while the agent looked is there now: no skip.
        to, why = (max(nxt, now), CHANGE) if nxt <= horizon else (horizon, TIMEOUT)
    if to >= limit:
        return max(now, limit), KILL_AT
    return to, why


def refusal(run: Run) -> WaitRefused | None:
    """Why `run` cannot take a wait now, or None when it can."""
    if run.closed_at is not None:
        return WaitRefused("this run is closed")
    if run.clock_mode != ClockMode.FAST_FORWARD:
        return WaitRefused(
            f"this run's clock is {run.clock_mode}: only a fast_forward run skips time on a "
            "wait (on a live clock, wait by sleeping; a virtual clock moves only by /advance)"
        )
    if run.status == RunStatus.COMPLETED:
        contacted = Event.objects.filter(
            run_id=run.pk, kind=EventKind.LIFECYCLE, type__in=(CONTACT_GET, CONTACT_POST)
        ).exists()
        if contacted:
            return WaitRefused("the agent has contacted the user: the task is over, no more waits")
        return WaitRefused("the run is completed: its time has run out")
    if run.status != RunStatus.RUNNING_AUTO or run.started_at is None:
        return WaitRefused("the clock has not started: open the task URL first")
    return None


def skip(
    run: Run, wait: Wait, *, wall: float | None = None, asked_at: float | None = None
) -> Skipped:
    """Take `wait` on `run` at wall time `wall` (default now; read once): move the clock, log the
    skip and fire what it passed. `asked_at`: the wall time the agent asked for it, when that
    was earlier (the wait was held back) — its lengths count from then. Raises WaitRefused when
    the run cannot wait."""
    wall = wall_now() if wall is None else wall
    if asked_at is not None:
        run.reread(*CLOCK_FIELDS)
        wait = wait.anchored(max(sim_now(run, asked_at), _last_skip_end(run)))
    for _ in range(MAX_ATTEMPTS):
        run.reread(*CLOCK_FIELDS, "closed_at")
        refused = refusal(run)
        if refused is not None:
            raise refused
        fire_due(run, wall=wall, reload=False)  # what is due already fires on time, before
        now, last_end = sim_now(run, wall), _last_skip_end(run)
        if now < last_end:  # read before the last skip was applied: it starts where that ended
            wall += (last_end - now) / run.speed_factor
            now = max(sim_now(run, wall), last_end)
        to, why = target(run, wait, now)
        if to <= now:
            return Skipped(now, now, why)
        seen = run.skipped
        with transaction.atomic():
            moved = Run.objects.filter(
                pk=run.pk,
                status=RunStatus.RUNNING_AUTO,
                closed_at__isnull=True,
                skipped=seen,
            ).update(skipped=_landing(run, wall, to))
            if not moved:
                continue  # another wait (or a contact) moved the run first: read it again
            run.reread(*CLOCK_FIELDS)
            append_event(
                run, EventKind.LIFECYCLE, SKIP, {"from": now, "to": to, "why": why}, at=now
            )
            fired = fire_through(run, to, on_time=False).fired
            if to >= run.event_timeline_end:
                fire_due(run, wall=wall, reload=False)  # the clock ran out: the run completes
        notify_clock_started(run)  # the ticker's schedule of this run is stale now
        notifications.clock_moved(run.pk)  # open pages re-render what the new time changes
        return Skipped(now, to, why, fired)
    raise LifecycleError("the run kept changing while the wait was applied; wait again")


def natural_end(run: Run, wait: Wait, *, wall: float) -> float | None:
    """The wall time at which `wait`, read at wall time `wall`, would end if the clock ran on
    instead of skipping (None: not started). A server that holds a wait back (it paces its
    agents: sentinel_site/pacing.py) lets it go by then, so it never lands later than it would
    have."""
    now = max(sim_now(run, wall), _last_skip_end(run))
    return wall_due(run, target(run, wait, now)[0])


def _last_skip_end(run: Run) -> float:
    """Where the run's last skip ended. A wait read at an older wall time than another that was
    applied first (two at once, or a request that arrived first but got here second) starts
    there, as if read when the clock showed it: from its own reading, the clock would read
    backwards by the difference (and the sum of skips would count it)."""
    if not run.skipped:
        return -math.inf
    last = (
        Event.objects.filter(run_id=run.pk, kind=EventKind.LIFECYCLE, type=SKIP)
        .order_by("-seq")
        .values_list("payload", flat=True)
        .first()
    )
    return last["to"] if last else -math.inf


def _landing(run: Run, wall: float, to: float) -> float:
    """The sum of skips with which the clock reads exactly `to` (not a rounding error short of
    it, which would leave the entry at `to` unfired by a later reading) at wall time `wall`."""
    ran = (wall - run.started_at) * run.speed_factor if run.started_at is not None else 0.0
    skipped = run.skipped + (to - sim_now(run, wall))
    while ran + skipped < to:
        skipped = math.nextafter(skipped, math.inf)
    return skipped
