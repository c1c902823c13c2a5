"""Entries due together are logged together: one transaction per chunk of them, each entry once,
in timeline order, at its own time (finding: a page read of a run with thousands of entries due
at once fired them one INSERT at a time, holding a request thread — one of the two every run's
pages share — for seconds)."""

from __future__ import annotations

import pytest
from django.db import connection
from django.test.utils import CaptureQueriesContext

from apps.scenarios.format import parse_scenario
from apps.tally.environment import tally_scenario
from events import lifecycle
from events.clock import wall_now
from events.models import ClockMode, Event, EventKind, Run
from events.projection import fold_from_scratch, state_at
from events.scheduler import FIRE_CHUNK, fire_due
from events.store import append_event

pytestmark = pytest.mark.django_db

DENSE = FIRE_CHUNK * 2 + 7  # three chunks, the last a short one


def started_run(times: list[float]) -> Run:
    """A live run, started ten minutes ago, whose pings fall at `times` (all due now)."""
    scenario = tally_scenario(pings=[(0.0, 1)] + [(t, 1) for t in times], condition_at=None)
    scenario["event_timeline_end"] = scenario["kill_at"] = 900.0
    run = lifecycle.create_run(parse_scenario(scenario).to_run_spec(), clock_mode=ClockMode.LIVE)
    lifecycle.start_clock(run)
    Run.objects.filter(pk=run.pk).update(started_at=wall_now() - 600)
    run.refresh_from_db()
    return run


def timed_entries(run: Run) -> list[tuple[int, int | None, float]]:
    return list(
        Event.objects.filter(run=run, kind=EventKind.SCENARIO, at__gt=0)
        .order_by("seq")
        .values_list("seq", "timeline_index", "at")
    )


def test_a_read_fires_a_dense_moment_in_a_few_statements_each_entry_once_in_order():
    times = [1.0 + i / 1000 for i in range(DENSE)]  # each its own moment, all long due
    run = started_run(times)
    with CaptureQueriesContext(connection) as queries:
        fired = fire_due(run)
    assert len(fired.fired) == DENSE
    assert len(queries) <= 6 * 3 + 4  # a few per chunk, not one per entry
    logged = timed_entries(run)
    seqs = [seq for seq, _, _ in logged]
    assert seqs == list(range(seqs[0], seqs[0] + DENSE))  # consecutive, nothing between
    assert [index for _, index, _ in logged] == list(range(1, DENSE + 1))
    assert [at for _, _, at in logged] == times  # each at its own scheduled time
    assert [e.seq for e in fired.fired] == seqs
    lateness = Event.objects.filter(run=run, timeline_index__gt=0).values_list("lateness_ms")
    assert all(ms > 0 for (ms,) in lateness)  # fired ten minutes late, and it says so
    assert fire_due(run).fired == []  # nothing twice
    assert state_at(run) == fold_from_scratch(run).state
    assert state_at(run).total == DENSE + 1


def test_entries_another_firer_logged_first_are_not_logged_again():
    run = started_run([1.0] * 10)
    # Another process fired entries 3 and 7 already; this one's hint lags behind them.
    for index in (3, 7):
        append_event(run, EventKind.SCENARIO, "ping", {"n": 1}, at=1.0, timeline_index=index)
    fired = fire_due(run)
    assert sorted(e.timeline_index for e in fired.fired) == [1, 2, 4, 5, 6, 8, 9, 10]
    indexes = [index for _, index, _ in timed_entries(run)]
    assert sorted(indexes) == list(range(1, 11))  # each exactly once
    assert state_at(run).total == 11
