"""The log: append-only, gap-free sequences, exactly-once firing, deterministic folds."""

from __future__ import annotations

import threading

import pytest
from django.db import connection

from events import store
from events.lifecycle import advance, create_run, start_clock
from events.models import ClockMode, Event, EventKind
from events.projection import fold_from_scratch, state_at
from events.scheduler import fire_due
from events.store import append_event
from events.ticker import tick

pytestmark = pytest.mark.django_db(transaction=True)


def _in_threads(count: int, target) -> None:
    errors: list[BaseException] = []

    def wrapped(index: int) -> None:
        try:
            target(index)
        except BaseException as exc:  # surface failures from worker threads
            errors.append(exc)
        finally:
            connection.close()  # kept ones would outlive the test database

    threads = [threading.Thread(target=wrapped, args=(i,)) for i in range(count)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert not errors, errors


def test_a_logged_event_can_be_neither_updated_nor_deleted(tally_spec):
    run = create_run(tally_spec())
    event = Event.objects.filter(run=run).first()
    with pytest.raises(PermissionError):
        Event.objects.filter(run=run).update(type="forged")
    with pytest.raises(PermissionError):
        Event.objects.filter(run=run).delete()
    with pytest.raises(PermissionError):
        event.save()
    with pytest.raises(PermissionError):
        event.delete()


def test_two_concurrent_writers_append_a_gap_free_sequence(tally_spec):
    run = create_run(tally_spec(pings=[]), clock_mode=ClockMode.VIRTUAL)
    before = Event.objects.filter(run=run).count()

    def writer(index: int) -> None:
        for n in range(500):
            append_event(
                run.pk, EventKind.ACTION, "poke", {"n": 1, "writer": index, "i": n}, at=0.0
            )

    _in_threads(2, writer)
    seqs = list(Event.objects.filter(run=run).order_by("seq").values_list("seq", flat=True))
    assert len(seqs) == before + 1000
    assert seqs == list(range(1, before + 1001))


def test_a_writer_that_lost_a_race_appends_at_its_next_attempt(tally_spec, monkeypatch):
    """The queue is fair: four writers hammering one run, and none needs a third attempt (a
    writer that keeps losing to a faster one would exhaust its attempts and lose its event)."""
    monkeypatch.setattr(store, "MAX_ATTEMPTS", 2)
    run = create_run(tally_spec(pings=[]), clock_mode=ClockMode.VIRTUAL)
    before = Event.objects.filter(run=run).count()

    def writer(index: int) -> None:
        for n in range(250):
            store.append_event(run.pk, EventKind.ACTION, "poke", {"writer": index, "i": n})

    _in_threads(4, writer)
    assert Event.objects.filter(run=run).count() == before + 1000


def test_a_busy_timeline_fires_every_entry_exactly_once_under_contention(tally_spec):
    pings = [(i * 0.5, 1) for i in range(200)]
    run = create_run(tally_spec(pings=pings, condition_at=None, eval_sql=None))
    start_clock(run, wall=run.created_at.timestamp() - 1000)  # the whole timeline is already due
    stop = threading.Event()

    def contender(index: int) -> None:
        if index == 0:
            while (
                not stop.is_set()
                and Event.objects.filter(run=run, timeline_index__isnull=False).count() < 200
            ):
                tick()
        else:
            for _ in range(30):
                fire_due(run.__class__.objects.get(pk=run.pk))

    _in_threads(5, contender)
    stop.set()
    fired = list(
        Event.objects.filter(run=run, kind=EventKind.SCENARIO).values_list(
            "timeline_index", flat=True
        )
    )
    assert sorted(fired) == list(range(200))


def test_the_cached_fold_equals_a_fold_from_scratch_at_every_seq(tally_spec):
    run = create_run(
        tally_spec(pings=[(t, 1) for t in range(0, 60, 3)]), clock_mode=ClockMode.VIRTUAL
    )
    for step in range(1, 60, 7):
        advance(run, float(step))
        append_event(run, EventKind.ACTION, "poke", {"n": step}, at=float(step))
    last = Event.objects.filter(run=run).count()
    for seq in range(last + 1):
        assert state_at(run, seq) == fold_from_scratch(run, seq).state
    # Walking forward one seq at a time exercises the fast-forward path of the cache.
    for seq in range(last + 1):
        assert state_at(run, seq).entries == fold_from_scratch(run, seq).state.entries
    assert state_at(run) == fold_from_scratch(run).state


def test_append_is_callable_from_async_code(tally_spec):
    import asyncio

    from events.store import aappend_event

    run = create_run(tally_spec(pings=[]), clock_mode=ClockMode.VIRTUAL)

    async def agent() -> list[int]:
        events = await asyncio.gather(
            *(aappend_event(run.pk, EventKind.ACTION, "poke", {"n": 1}, at=0.0) for _ in range(10))
        )
        return sorted(e.seq for e in events)

    seqs = asyncio.run(agent())
    assert len(set(seqs)) == 10
    assert seqs[-1] == Event.objects.filter(run=run).count()


def test_an_appended_event_comes_back_as_stored_and_cannot_be_saved_again(tally_spec):
    run = create_run(tally_spec(pings=[]), clock_mode=ClockMode.VIRTUAL)
    event = append_event(
        run, EventKind.ACTION, "poke", {"n": 2, "note": "ü"}, at=1.5, recorded_at=7.0
    )
    stored = Event.objects.get(pk=event.pk)
    assert (
        stored.seq,
        stored.run_id,
        stored.at,
        stored.kind,
        stored.type,
        stored.payload,
        stored.recorded_at,
    ) == (event.seq, run.pk, 1.5, "action", "poke", {"n": 2, "note": "ü"}, 7.0)
    assert event.seq == Event.objects.filter(run=run).count()
    with pytest.raises(PermissionError):
        event.save()  # it is a logged row, not a new one


def test_appends_inside_a_callers_transaction_commit_or_roll_back_with_it(tally_spec):
    from django.db import transaction

    run = create_run(tally_spec(pings=[]), clock_mode=ClockMode.VIRTUAL)
    before = Event.objects.filter(run=run).count()
    with transaction.atomic():
        first = append_event(run, EventKind.ACTION, "poke", {"n": 1})
        second = append_event(run, EventKind.ACTION, "poke", {"n": 1})
    assert (first.seq, second.seq) == (before + 1, before + 2)
    with pytest.raises(RuntimeError), transaction.atomic():
        append_event(run, EventKind.ACTION, "poke", {"n": 1})
        raise RuntimeError("the caller changes its mind")
    assert Event.objects.filter(run=run).count() == before + 2


def test_a_run_is_found_by_token_only_while_open_with_its_scenario_read_lazily(tally_spec):
    from events.lifecycle import close
    from events.models import Run

    run = create_run(tally_spec(pings=[]), clock_mode=ClockMode.VIRTUAL)
    found = Run.objects.open_by_token(run.token)
    assert found.pk == run.pk
    assert found.created_at == Run.objects.get(pk=run.pk).created_at  # converted, tz-aware
    assert found.get_deferred_fields() == {"scenario"}
    assert found.spec == run.scenario
    assert Run.objects.open_by_token("no-such-token") is None
    close(run)
    assert Run.objects.open_by_token(run.token) is None
