"""The scheduler's per-process hint (events/scheduler.py: the first timeline entry a process
knows is not fired yet) is only a shortcut. Other processes fire entries behind its back, so a
process's hint lags; a restarted process has none. Whatever the hint, every timeline entry
fires exactly once, in order — and when nothing is due the hint spares the query.

Each server process has its own hints. `Process` stands in for one: while it is entered,
`fire_due` (and whatever calls it) sees only that process's memory. The module keeps that memory
in `_next_unfired`; swapping it is the one way to have two processes in one test.
"""

from __future__ import annotations

from typing import Self

import pytest

from events import lifecycle, scheduler
from events.models import ClockMode, Event, EventKind, Run
from events.scheduler import fire_due

pytestmark = pytest.mark.django_db

TIMES = [0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0]
START = 1_700_000_000.0  # wall clock reading when the live clock starts (speed 1)


class Process:
    """Another server process, with its own (initially empty) memory of hints."""

    def __init__(self) -> None:
        self.hints: dict = {}
        self._saved: dict | None = None

    def __enter__(self) -> Self:
        self._saved, scheduler._next_unfired = scheduler._next_unfired, self.hints
        return self

    def __exit__(self, *exc) -> None:
        scheduler._next_unfired = self._saved


def at(t: float) -> float:
    """The wall time at which the live clock reads `t`."""
    return START + t


def pings(tally_spec) -> dict:
    return tally_spec(pings=[(t, 1) for t in TIMES], condition_at=None, eval_sql=None)


@pytest.fixture
def live_run(tally_spec):
    """A run of eight pings, 10 s apart; the first fired at creation, the clock started at START."""
    run = lifecycle.create_run(pings(tally_spec))
    return lifecycle.start_clock(run, wall=START)


@pytest.fixture
def virtual_run(tally_spec):
    return lifecycle.create_run(pings(tally_spec), clock_mode=ClockMode.VIRTUAL)


def fired(run) -> list[int]:
    """Timeline indexes of the logged scenario events, in log order."""
    return list(
        Event.objects.filter(run=run, kind=EventKind.SCENARIO)
        .order_by("seq")
        .values_list("timeline_index", flat=True)
    )


def assert_fired_once_in_order(run, count: int) -> None:
    assert fired(run) == list(range(count))
    times = Event.objects.filter(run=run, kind=EventKind.SCENARIO).order_by("seq")
    assert [e.at for e in times] == TIMES[:count]


def indexes(result) -> list[int]:
    return [event.timeline_index for event in result.fired]


READS = {
    # The caller's copy, reloaded by fire_due itself.
    "reloaded": lambda run: {"run": run, "reload": True},
    # A new instance read from the database just now (as a page view does).
    "read afresh": lambda run: {"run": Run.objects.get(pk=run.pk), "reload": False},
}


@pytest.mark.parametrize("read", READS)
def test_lagging_processes_skip_nothing_and_fire_nothing_twice(live_run, read):
    def fire(t: float) -> list[int]:
        return indexes(fire_due(**READS[read](live_run), wall=at(t)))

    first, second = Process(), Process()
    with first:
        assert fire(15) == [1]
    with second:
        assert fire(45) == [2, 3, 4]
    with first:  # its hint still says 2
        assert fire(65) == [5, 6]
    with second:  # its hint still says 5
        assert fire(65) == []
    assert fire(75) == [7]  # this process's hint has said 1 since the run was created
    assert_fired_once_in_order(live_run, len(TIMES))


@pytest.mark.parametrize("read", READS)
def test_a_process_without_hints_starts_from_the_log(live_run, read):
    assert indexes(fire_due(live_run, wall=at(35))) == [1, 2, 3]
    with Process():  # a process that has never seen the run, e.g. just restarted
        assert indexes(fire_due(**READS[read](live_run), wall=at(35))) == []
        assert indexes(fire_due(**READS[read](live_run), wall=at(45))) == [4]
    assert indexes(fire_due(**READS[read](live_run), wall=at(55))) == [5]
    assert_fired_once_in_order(live_run, 6)


def test_a_forgotten_hint_costs_a_query_not_an_entry(live_run, tally_spec, monkeypatch):
    other = lifecycle.start_clock(lifecycle.create_run(pings(tally_spec)), wall=START)
    monkeypatch.setattr(scheduler, "HINTS_KEPT", 1)  # each run's hint pushes out the other's
    for t in (5, 15, 15, 38, 52, 52, 75):
        for run in (live_run, other):
            fire_due(Run.objects.get(pk=run.pk), wall=at(t), reload=False)
    assert_fired_once_in_order(live_run, len(TIMES))
    assert_fired_once_in_order(other, len(TIMES))


def test_a_tracking_callers_lagging_next_index_fires_only_what_is_left(live_run):
    # The ticker passes its own position; page views may have fired further meanwhile.
    assert indexes(fire_due(live_run, wall=at(25))) == [1, 2]
    assert indexes(fire_due(live_run, wall=at(45), next_index=1)) == [3, 4]
    result = fire_due(live_run, wall=at(45), next_index=0)
    assert indexes(result) == [] and result.next_index == 5
    assert_fired_once_in_order(live_run, 5)


def test_when_nothing_is_due_a_page_view_costs_no_query(live_run, django_assert_num_queries):
    fire_due(live_run, wall=at(25))
    # Callers that lag (an old position, an older clock reading) do not lower the hint.
    fire_due(live_run, wall=at(15), next_index=0)
    run = Run.objects.get(pk=live_run.pk)
    with django_assert_num_queries(0):
        result = fire_due(run, wall=at(29), reload=False)
    assert result.fired == [] and result.next_index == 3


def test_a_virtual_clock_advanced_by_another_process(virtual_run):
    other = Process()
    with other:
        assert indexes(lifecycle.advance(virtual_run, 35)) == [1, 2, 3]
    # This process's hint still says 1: a page view finds 1–3 fired and fires nothing.
    assert indexes(fire_due(Run.objects.get(pk=virtual_run.pk), reload=False)) == []
    with other:
        assert indexes(lifecycle.advance(virtual_run, 55)) == [4, 5]
    assert indexes(lifecycle.advance(virtual_run, 75)) == [6, 7]
    with other:
        assert indexes(fire_due(Run.objects.get(pk=virtual_run.pk), reload=False)) == []
    assert_fired_once_in_order(virtual_run, len(TIMES))
