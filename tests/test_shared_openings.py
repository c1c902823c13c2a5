"""What one run's fold and grading database share with another run of the same scenario (issue
#29): the fold of the log's opening (init and the t ≤ 0 preloads) and the serialised grading
tables of one state at one moment. Neither may hide an event logged after it."""

from __future__ import annotations

import pytest

from events import lifecycle, projection
from events.commands import perform_action
from events.evaluation import evaluate, grading_snapshot
from events.models import ClockMode

pytestmark = pytest.mark.django_db

AT_LEAST_TWO = "SELECT (SELECT SUM(n) FROM entries) >= 2"


def virtual_run(tally_spec, **kwargs):
    return lifecycle.create_run(tally_spec(**kwargs), clock_mode=ClockMode.VIRTUAL)


def test_runs_of_one_scenario_share_the_fold_of_their_opening(tally_spec):
    first, second = virtual_run(tally_spec), virtual_run(tally_spec)
    assert projection.folded_state(first).state is projection.folded_state(second).state


def test_an_opening_with_another_preload_is_folded_for_itself(tally_spec):
    one = virtual_run(tally_spec, pings=[(0.0, 1), (10.0, 1)])
    five = virtual_run(tally_spec, pings=[(0.0, 5), (10.0, 1)])
    assert projection.folded_state(one).state.total == 1
    assert projection.folded_state(five).state.total == 5


def test_events_after_the_shared_opening_are_folded(tally_spec):
    projection.folded_state(virtual_run(tally_spec))  # the opening is kept
    run = virtual_run(tally_spec)
    lifecycle.advance(run, 10)  # the ping at 10 s
    perform_action(run, "poke", {"n": 4})
    projection.clear_cache()
    projection.folded_state(virtual_run(tally_spec))  # kept again, from another run
    folded = projection.folded_state(run)
    assert folded.state.total == 1 + 1 + 4
    assert folded.state == projection.fold_from_scratch(run).state


def test_a_grading_database_is_built_once_per_state_and_moment(tally_spec):
    run = virtual_run(tally_spec)
    snapshot = grading_snapshot(run)
    assert snapshot.serialised() is grading_snapshot(virtual_run(tally_spec)).serialised()
    later = grading_snapshot(run, now=5.0)  # another moment: tables of its own
    assert later.serialised() is not snapshot.serialised()


def test_an_event_after_a_graded_position_is_graded(tally_spec):
    run = virtual_run(tally_spec, eval_sql=AT_LEAST_TWO, condition_at=None)
    before = grading_snapshot(run)
    before.serialised()  # kept for the preload's state
    perform_action(run, "poke", {"n": 1})
    after = grading_snapshot(run)
    assert after.state is not before.state
    assert after.serialised() != before.serialised()
    lifecycle.advance(run, 1)
    assert evaluate(run).success is True  # graded on the tally the poke raised to 2


def test_the_shared_opening_grades_as_a_fold_from_scratch(tally_spec):
    kept = virtual_run(tally_spec, eval_sql=AT_LEAST_TWO, condition_at=None)
    evaluate(kept)  # the opening's state and its grading database are kept
    run = virtual_run(tally_spec, eval_sql=AT_LEAST_TWO, condition_at=None)
    lifecycle.advance(run, 10)  # the ping at 10 s makes it 2
    assert evaluate(run).success is True
    assert (
        evaluate(virtual_run(tally_spec, eval_sql=AT_LEAST_TWO, condition_at=None)).success is False
    )


@pytest.mark.parametrize("environment", ["microdin", "microfy", "micromail", "microhood"])
def test_a_shared_full_preload_equals_its_fold_from_scratch(environment):
    from apps.bench.management.commands.bench_protocol import full_preload_scenario

    spec = full_preload_scenario(environment)
    projection.folded_state(lifecycle.create_run(spec, clock_mode=ClockMode.VIRTUAL))  # kept
    run = lifecycle.create_run(spec, clock_mode=ClockMode.VIRTUAL)
    shared, scratch = projection.folded_state(run), projection.fold_from_scratch(run)
    assert shared.state == scratch.state
    assert dict(shared.baselines) == dict(scratch.baselines)
    assert (shared.seq, shared.live_seq) == (scratch.seq, scratch.live_seq)
