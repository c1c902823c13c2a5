"""The ticker fires in bounded batches, each due run in turn (finding: a run with 15,000
entries due at once fired them in one loop, delaying every other run's events by seconds; and
entries were still written after the run was closed)."""

from __future__ import annotations

import pytest

from apps.scenarios.format import parse_scenario
from apps.tally.environment import tally_scenario
from events import lifecycle
from events.clock import wall_now
from events.models import ClockMode, Event, EventKind, Run
from events.scheduler import TICK_BATCH
from events.ticker import Schedule

pytestmark = pytest.mark.django_db


def due_run(pings: int) -> Run:
    """A live run, started a minute ago, with `pings` entries all due at t=1."""
    scenario = tally_scenario(pings=[(0.0, 1)] + [(1.0, 1)] * pings, condition_at=None)
    run = lifecycle.create_run(parse_scenario(scenario).to_run_spec(), clock_mode=ClockMode.LIVE)
    lifecycle.start_clock(run)
    Run.objects.filter(pk=run.pk).update(started_at=wall_now() - 60)
    return run


def fired(run: Run) -> int:
    return Event.objects.filter(run=run, kind=EventKind.SCENARIO, at__gt=0).count()


def test_a_dense_run_fires_a_batch_per_turn_and_every_other_due_run_has_its_turn():
    dense, quiet = due_run(3 * TICK_BATCH), due_run(2)
    schedule = Schedule()
    assert schedule.tick() == 0.0  # more is due: no sleep
    assert (fired(dense), fired(quiet)) == (TICK_BATCH, 2)
    while schedule.tick() == 0.0 and fired(dense) < 3 * TICK_BATCH:
        pass
    assert fired(dense) == 3 * TICK_BATCH  # all of it, in the end, each once
    indexes = Event.objects.filter(run=dense, timeline_index__gt=0).values_list("timeline_index")
    assert sorted(i for (i,) in indexes) == list(range(1, 3 * TICK_BATCH + 1))


def test_a_run_closed_between_batches_fires_no_more():
    dense = due_run(3 * TICK_BATCH)
    schedule = Schedule()
    schedule.tick()
    lifecycle.close(dense)
    schedule.tick()
    schedule.tick()
    assert fired(dense) == TICK_BATCH
