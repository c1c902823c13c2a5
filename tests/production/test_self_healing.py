"""Finding 10: the production shape survives a Redis outage and processes killed under it.

Both tickers are tried (its own process; Celery worker + beat). Timelines are started through
the site and then left alone: nobody reads the runs, so only the supervised ticker can fire
their entries. Lateness is printed, never asserted (speed is bench_scale's job).
"""

from __future__ import annotations

import os
import signal
import statistics
import time

import pytest

from apps.tally.environment import tally_scenario
from events.models import Event, Run, RunStatus
from sentinel_site.figures import percentile
from tests.control_api import post

pytestmark = [
    pytest.mark.django_db(transaction=True),
    pytest.mark.e2e,
    pytest.mark.production_shape,
]

SPEED = 4.0
PATIENCE_S = 90.0  # how long a test waits for the ticker before calling it dead


def start_live_run(site, *, every: float, until: float) -> tuple[int, int]:
    """A tally run with a ping every `every` simulated seconds up to `until`, clock started.
    Returns (run id, number of timed entries)."""
    times = [round(every * i, 3) for i in range(1, int(until / every) + 1)]
    scenario = tally_scenario(
        pings=[(0.0, 1)] + [(t, 1) for t in times], condition_at=None, scenario_id="healing"
    )
    scenario["event_timeline_end"] = scenario["kill_at"] = until + every
    run = post(site.base_url, "/api/runs/", {"scenario_json": scenario, "speed_factor": SPEED})
    post(site.base_url, f"/api/runs/{run['id']}/start/")
    return run["id"], len(times)


def fired_by_the_ticker(run_id: int, expected: int) -> list[float]:
    """Wait until the ticker has completed the run; the lateness of its timed entries."""
    deadline = time.monotonic() + PATIENCE_S
    while Run.objects.get(pk=run_id).status != RunStatus.COMPLETED:
        assert time.monotonic() < deadline, f"run {run_id} never completed: the ticker is dead"
        time.sleep(0.5)
    entries = list(
        Event.objects.filter(run_id=run_id, timeline_index__isnull=False, at__gt=0).values_list(
            "timeline_index", "lateness_ms"
        )
    )
    indexes = [index for index, _ in entries]
    assert sorted(indexes) == list(range(1, expected + 1)), "an entry did not fire exactly once"
    return [lateness for _, lateness in entries]


def all_running(site) -> dict:
    states = site.wait_until_running(PATIENCE_S)
    assert sorted(states) == sorted(site.shape.programs)
    return states


def test_timelines_fire_through_and_after_a_redis_outage(production, redis_server):
    through, through_count = start_live_run(production, every=2.0, until=60.0)  # 15 wall s
    time.sleep(2.0)
    redis_server.stop()
    time.sleep(3.0)
    redis_server.start()
    time.sleep(2.0)
    after, after_count = start_live_run(production, every=2.0, until=24.0)

    fired_by_the_ticker(through, through_count)
    lateness = fired_by_the_ticker(after, after_count)
    all_running(production)
    print(
        f"{production.shape.ticker} ticker after the outage: lateness p50={percentile(lateness, 50):.1f} ms "
        f"max={max(lateness):.1f} ms"
    )


def test_killed_processes_are_restarted_and_beat_is_never_orphaned(production):
    before = all_running(production)
    ticker = "ticker:ticker-0" if production.shape.ticker == "process" else "worker"
    killed = (ticker, "web:web-0")
    for name in killed:
        os.kill(before[name][1], signal.SIGKILL)

    deadline = time.monotonic() + PATIENCE_S
    while True:
        after = production.states()
        restarted = all(
            after.get(name, ("", None))[0] == "RUNNING" and after[name][1] != before[name][1]
            for name in killed
        )
        if restarted:
            break
        assert time.monotonic() < deadline, f"not restarted: {after}"
        time.sleep(0.2)
    untouched = [name for name in before if name not in killed]
    assert {n: after[n] for n in untouched} == {n: before[n] for n in untouched}, (
        "only the killed processes were replaced (beat is its own program, never orphaned)"
    )

    run, count = start_live_run(production, every=2.0, until=12.0)
    fired_by_the_ticker(run, count)


def test_a_standby_ticker_keeps_timelines_firing_while_the_other_is_down(production):
    if production.shape.ticker != "process":
        pytest.skip("the standby is the ticker process's (Celery's worker is restarted instead)")
    all_running(production)
    production.ctl("stop", "ticker:ticker-0")  # down, and not restarted until told
    try:
        run, count = start_live_run(production, every=1.0, until=8.0)
        lateness = fired_by_the_ticker(run, count)  # only ticker-1 was there to fire them
        # The standby was firing all along (firing is idempotent): nothing waits for a
        # takeover, so the entries due meanwhile fire within a second of their moment.
        assert statistics.median(lateness) < 1000, lateness
    finally:
        production.ctl("start", "ticker:ticker-0")
    all_running(production)


def test_a_new_start_elsewhere_never_stops_a_running_set(production, tmp_path):
    from sentinel_site.production import Shape, stop_stale

    running = set(production.pids())
    assert not running & set(stop_stale(Shape(run_dir=tmp_path / "other"), grace_s=0))
    assert production.pids() and set(production.pids()) == running
