"""Fast-forward clocks: a declared wait skips the run's clock ahead (events/fastforward.py).

The cast: a tally run whose pings arrive every 10 simulated seconds, its clock started at a
known wall moment, so the clock reads exactly `(wall − START) × speed + skipped`.
"""

from __future__ import annotations

import threading

import pytest
from django.db import connection

from events import lifecycle
from events.clock import sim_now, wall_now
from events.evaluation import evaluate
from events.fastforward import (
    CHANGE,
    KILL_AT,
    SKIP,
    SLEPT,
    TIMEOUT,
    Wait,
    WaitRefused,
    skip,
)
from events.models import ClockMode, Event, EventKind, Run
from events.scheduler import fire_due

START = 1_700_000_000.0
PINGS = [0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0]


def timeline_order(run: Run) -> list[int]:
    """The timeline indexes of the run's fired entries, in log order."""
    return list(
        Event.objects.filter(run=run, kind=EventKind.SCENARIO)
        .order_by("seq")
        .values_list("timeline_index", flat=True)
    )


def skips(run: Run) -> list[dict]:
    return list(
        Event.objects.filter(run=run, kind=EventKind.LIFECYCLE, type=SKIP)
        .order_by("seq")
        .values_list("payload", flat=True)
    )


@pytest.fixture
def pings_spec(tally_spec):
    return tally_spec(pings=[(t, 1) for t in PINGS], condition_at=30.0)


def fast_forward_run(spec, *, wall: float = START, speed: float = 1.0) -> Run:
    run = lifecycle.create_run(spec, clock_mode=ClockMode.FAST_FORWARD, speed_factor=speed)
    return lifecycle.start_clock(run, wall=wall)


@pytest.mark.django_db
class TestOneSkip:
    def test_a_sleep_fires_exactly_the_entries_it_passes_in_order_after_its_own_log_entry(
        self, pings_spec
    ):
        run = fast_forward_run(pings_spec)
        done = skip(run, Wait(seconds=35.0), wall=START + 2.0)  # from 2 s to 37 s
        assert (done.start, done.end, done.why) == (2.0, 37.0, SLEPT)
        assert [event.at for event in done.fired] == [10.0, 20.0, 30.0]
        assert timeline_order(run) == [0, 1, 2, 3]
        assert skips(run) == [{"from": 2.0, "to": 37.0, "why": SLEPT}]
        logged_skip = Event.objects.get(run=run, type=SKIP)
        assert logged_skip.seq < min(event.seq for event in done.fired)
        # Passed entries were never due on a wall clock: no lateness is made up for them.
        assert {event.lateness_ms for event in done.fired} == {None}

    def test_the_clock_reads_started_at_speed_and_the_sum_of_skips(self, pings_spec):
        run = fast_forward_run(pings_spec, speed=2.0)
        skip(run, Wait(seconds=15.0), wall=START + 1.0)  # 2 s in, then 15 skipped
        skip(run, Wait(seconds=5.0), wall=START + 3.0)  # 21 s in, then 5 more
        run.refresh_from_db()
        assert run.skipped == 20.0
        assert sim_now(run, START + 4.0) == (4.0 * 2.0) + 20.0
        # Nothing later than the clock reads was fired: the next ping (30 s) is still ahead.
        fire_due(run, wall=START + 4.0)
        assert timeline_order(run) == [0, 1, 2]

    def test_a_wait_read_before_one_applied_first_starts_where_that_one_ended(self, pings_spec):
        run = fast_forward_run(pings_spec)
        skip(run, Wait(seconds=10.0), wall=START + 5.0)  # from 5 s to 15 s
        later = skip(run, Wait(seconds=10.0), wall=START + 3.0)  # read at 3 s, applied second
        assert (later.start, later.end) == (15.0, 25.0)
        assert [s["from"] for s in skips(run)] == [5.0, 15.0]  # the clock never read backwards
        run.refresh_from_db()
        assert run.skipped == 20.0  # the sum of the two skips, nothing more

    def test_until_change_stops_at_the_next_entry_and_fires_it(self, pings_spec):
        run = fast_forward_run(pings_spec)
        done = skip(run, Wait(until_change=True, timeout=60.0), wall=START + 12.0)
        assert (done.start, done.end, done.why) == (12.0, 20.0, CHANGE)
        assert [event.timeline_index for event in done.fired] == [2]

    def test_until_change_stops_at_its_timeout_when_nothing_comes_sooner(self, pings_spec):
        run = fast_forward_run(pings_spec)
        done = skip(run, Wait(until_change=True, timeout=3.0), wall=START + 12.0)
        assert (done.end, done.why, done.fired) == (15.0, TIMEOUT, [])
        assert skips(run) == [{"from": 12.0, "to": 15.0, "why": TIMEOUT}]

    def test_a_wait_never_passes_kill_at(self, pings_spec):
        run = fast_forward_run(pings_spec)  # kill_at 630, timeline end 720
        done = skip(run, Wait(seconds=5000.0), wall=START + 1.0)
        assert (done.end, done.why) == (630.0, KILL_AT)
        assert sim_now(run, START + 1.0) == 630.0
        again = skip(run, Wait(until_change=True), wall=START + 1.0)  # nothing left to skip
        assert (again.start, again.end, again.why) == (630.0, 630.0, KILL_AT)
        assert len(skips(run)) == 1  # an empty skip is not logged
        assert run.status == "running_auto"  # the clock still runs on to the timeline end

    def test_a_wait_held_back_counts_its_lengths_from_when_it_was_asked(self, pings_spec):
        # Asked at 2 s, let go at 5 s by a server that paces its agents: the entry at 10 s is
        # still the next change, and a timeout of 20 s still ends at 22 s, not at 25 s.
        run = fast_forward_run(pings_spec)
        done = skip(run, Wait(seconds=20.0), wall=START + 5.0, asked_at=START + 2.0)
        assert (done.start, done.end, done.why) == (5.0, 22.0, SLEPT)
        changed = skip(
            run, Wait(until_change=True, timeout=30.0), wall=START + 5.5, asked_at=START + 5.2
        )
        assert (changed.start, changed.end, changed.why) == (22.5, 30.0, CHANGE)
        timed_out = skip(
            run, Wait(until_change=True, timeout=4.0), wall=START + 6.0, asked_at=START + 5.6
        )
        # Asked at 30.1 s (the clock ran 0.1 s since the last skip): ends at 34.1, not 34.5.
        assert timed_out.start == pytest.approx(30.5)
        assert (timed_out.end, timed_out.why) == (pytest.approx(34.1), TIMEOUT)

    @pytest.mark.parametrize(
        ("wait", "anchored"),
        [
            (Wait(seconds=5.0), Wait(to=15.0)),
            (Wait(to=12.0), Wait(to=12.0)),
            (Wait(until_change=True), Wait(until_change=True, since=10.0)),
            (Wait(until_change=True, timeout=7.0), Wait(until_change=True, to=17.0, since=10.0)),
            (
                Wait(until_change=True, to=30.0, since=4.0),
                Wait(until_change=True, to=30.0, since=4.0),
            ),
        ],
    )
    def test_a_wait_anchored_at_a_moment_names_moments_not_lengths(self, wait, anchored):
        assert wait.anchored(10.0) == anchored

    def test_a_zero_second_sleep_reads_the_clock_and_logs_nothing(self, pings_spec):
        run = fast_forward_run(pings_spec)
        done = skip(run, Wait(seconds=0.0), wall=START + 4.0)
        assert (done.start, done.end) == (4.0, 4.0)
        assert skips(run) == []


@pytest.mark.django_db
class TestRefusals:
    @pytest.mark.parametrize("mode", [ClockMode.LIVE, ClockMode.VIRTUAL])
    def test_live_and_virtual_runs_refuse_naming_their_clock(self, pings_spec, mode):
        run = lifecycle.create_run(pings_spec, clock_mode=mode)
        if mode == ClockMode.LIVE:
            lifecycle.start_clock(run, wall=START)
        with pytest.raises(WaitRefused, match=f"clock is {mode.value}") as refused:
            skip(run, Wait(seconds=10.0), wall=START + 1.0)
        assert refused.value.status == 409
        assert skips(run) == []

    def test_a_fast_forward_run_not_started_yet_says_to_open_the_task(self, pings_spec):
        run = lifecycle.create_run(pings_spec, clock_mode=ClockMode.FAST_FORWARD)
        with pytest.raises(WaitRefused, match="open the task URL"):
            skip(run, Wait(seconds=10.0))

    def test_after_contact_a_wait_is_refused_and_the_clock_stays_frozen(self, pings_spec):
        run = fast_forward_run(pings_spec, wall=wall_now() - 5.0)
        lifecycle.contact(run, method="POST", message="done")
        frozen = run.sim_time
        with pytest.raises(WaitRefused, match="contacted"):
            skip(run, Wait(seconds=60.0))
        run.refresh_from_db()
        assert run.sim_time == frozen and run.skipped == 0.0


@pytest.mark.django_db(transaction=True)
class TestConcurrency:
    def test_two_concurrent_waits_skip_one_after_the_other_and_fire_each_entry_once(
        self, tally_spec
    ):
        pings = [(float(t), 1) for t in range(0, 400, 5)]
        run = fast_forward_run(
            tally_spec(pings=pings, condition_at=None, eval_sql=None), wall=wall_now()
        )
        barrier = threading.Barrier(2)
        errors: list[BaseException] = []

        def waiter() -> None:
            try:
                barrier.wait()
                skip(Run.objects.get(pk=run.pk), Wait(seconds=150.0))
            except BaseException as exc:
                errors.append(exc)
            finally:
                connection.close()  # kept ones would outlive the test database

        threads = [threading.Thread(target=waiter) for _ in range(2)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        assert not errors, errors
        run.refresh_from_db()
        assert run.skipped == pytest.approx(300.0)
        first, second = skips(run)
        assert second["from"] >= first["to"]  # the second started where the first left off
        # Fired: every entry up to where the second skip stopped (no ticker here: entries the
        # wall clock brings due after it, on a slow machine, are nobody's to fire yet).
        due = [i for i, (t, _) in enumerate(pings) if t <= second["to"]]
        assert sorted(timeline_order(run)) == timeline_order(run)  # in timeline order …
        assert timeline_order(run) == due  # … each once, none missing

    def test_waits_with_the_ticker_running_fire_every_entry_once_in_order(
        self, tally_spec, running_ticker
    ):
        pings = [(float(t), 1) for t in range(0, 600, 3)]
        run = fast_forward_run(
            tally_spec(pings=pings, condition_at=None, eval_sql=None), wall=wall_now()
        )
        for _ in range(12):
            skip(run, Wait(until_change=True, timeout=40.0))
            skip(run, Wait(seconds=17.0))
        now = sim_now(run, wall_now())
        expected = [i for i, (t, _) in enumerate(pings) if t <= now]
        # The ticker catches up with the running clock too; whatever fired, fired once, in order.
        fired = timeline_order(run)
        assert fired == sorted(set(fired))
        assert fired[: len(expected)] == expected

    def test_an_action_posted_during_skips_is_logged_never_lost(self, pings_spec):
        from events.commands import perform_action

        run = fast_forward_run(pings_spec, wall=wall_now())
        errors: list[BaseException] = []

        def poker() -> None:
            try:
                for _ in range(20):
                    perform_action(Run.objects.get(pk=run.pk), "poke", {"n": 1})
            except BaseException as exc:
                errors.append(exc)
            finally:
                connection.close()  # kept ones would outlive the test database

        thread = threading.Thread(target=poker)
        thread.start()
        for _ in range(10):
            skip(Run.objects.get(pk=run.pk), Wait(seconds=5.0))
        thread.join()
        assert not errors, errors
        assert Event.objects.filter(run=run, kind=EventKind.ACTION).count() == 20
        assert len(skips(run)) == 10


@pytest.mark.django_db
def test_a_fast_forward_run_is_graded_on_simulated_time_and_replays_exactly(pings_spec, tmp_path):
    import io

    from django.core.management import call_command

    run = fast_forward_run(pings_spec, wall=wall_now())
    skip(run, Wait(until_change=True, timeout=100.0))  # to 10 s
    skip(run, Wait(until_change=True, timeout=100.0))  # to 20 s
    skip(run, Wait(until_change=True, timeout=100.0))  # to 30 s: the tally reaches 3
    lifecycle.contact(run, method="POST", message="the tally is 3")
    verdict = evaluate(run)
    assert verdict.success, verdict.detail

    exported = tmp_path / "run.jsonl"
    exported.write_text(_command(call_command, io, "export_run", str(run.pk)))
    copy_id = int(_command(call_command, io, "import_run", str(exported)).strip())
    copy = Run.objects.get(pk=copy_id)
    assert copy.clock_mode == ClockMode.FAST_FORWARD and copy.skipped == run.skipped
    assert skips(copy) == skips(run) and timeline_order(copy) == timeline_order(run)
    assert "match:" in _command(call_command, io, "replay", str(copy_id))


def _command(call_command, io, *args: str) -> str:
    out = io.StringIO()
    call_command(*args, stdout=out, stderr=io.StringIO())
    return out.getvalue()


@pytest.mark.django_db
def test_time_travel_shows_the_skip_and_the_world_just_before_and_after_it(
    pings_spec, admin_client
):
    run = fast_forward_run(pings_spec, wall=wall_now())
    skip(run, Wait(seconds=25.0))  # passes the pings at 10 and 20 s
    timeline = admin_client.get(f"/admin/events/run/{run.pk}/timeline/").content.decode()
    assert "<td>skip</td>" in timeline and "&quot;why&quot;: &quot;slept&quot;" in timeline
    the_skip = Event.objects.get(run=run, type=SKIP)
    before = admin_client.get(f"/admin/events/run/{run.pk}/at/{the_skip.seq}/site/")
    after = admin_client.get(f"/admin/events/run/{run.pk}/at/{the_skip.seq + 2}/site/")
    assert before.status_code == after.status_code == 200
    assert tally_of(before.content.decode()) == 1 and tally_of(after.content.decode()) == 3


def tally_of(html: str) -> int:
    import re

    return int(re.search(r'<output id="total">(\d+)</output>', html).group(1))
