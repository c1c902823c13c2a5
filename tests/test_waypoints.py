"""Values between waypoints: the original's price/star formula, and when a shown value changes."""

from __future__ import annotations

import bisect
import random

import pytest

from apps.kit.waypoints import Waypoints


def original(start: float, inserted: list[tuple[float, float]], now: float) -> float:
    """The original's model, written from its description (upstream-env-microhood.md §3):
    insert (seeding (0, start) into an empty list for a time > 0, after equal or earlier
    times), then right-bisect and interpolate."""
    points: list[list[float]] = []
    for at, value in inserted:
        if not points and at > 0:
            points.append([0, start])
        times = [p[0] for p in points]
        points.insert(bisect.bisect_right(times, at), [at, value])
    if not points:
        return start
    if now <= points[0][0]:
        return points[0][1]
    if now >= points[-1][0]:
        return points[-1][1]
    i = bisect.bisect_right([p[0] for p in points], now) - 1
    (t0, p0), (t1, p1) = points[i], points[i + 1]
    return p0 + (p1 - p0) * (now - t0) / (t1 - t0)


def test_no_waypoints_is_flat_at_the_start_value():
    assert Waypoints(180.0).value_at(0) == Waypoints(180.0).value_at(700) == 180.0


def test_a_series_ramps_from_the_start_value_to_each_waypoint_and_holds_after_the_last():
    volt = Waypoints(200.0).with_points([(348.67, 222.0), (720.0, 240.0)])
    assert volt.value_at(0) == 200.0
    assert volt.value_at(348.67 / 2) == pytest.approx(211.0)
    assert volt.value_at(348.67) == 222.0
    assert volt.value_at(534.335) == pytest.approx(231.0)
    assert volt.value_at(900) == 240.0


def test_a_waypoint_at_zero_overrides_the_start_value_without_a_seed():
    assert Waypoints(100.0).with_point(0, 90.0).points == ((0.0, 90.0),)
    assert Waypoints(100.0).with_point(0, 90.0).value_at(50) == 90.0


def test_a_point_fired_later_is_a_step_then_holds():
    # A set_price / stars_waypoint event is inserted only when it fires: the value jumps then.
    before = Waypoints(50.0)
    after = before.with_point(120.0, 80.0)
    assert before.value_at(120.0) == 50.0
    assert after.value_at(120.0) == 80.0 and after.value_at(300) == 80.0


def test_ties_keep_the_order_they_were_added_in():
    series = Waypoints(10.0).with_points([(5.0, 1.0), (5.0, 2.0)])
    assert series.points == ((0.0, 10.0), (5.0, 1.0), (5.0, 2.0))
    assert series.value_at(5.0) == original(10.0, [(5.0, 1.0), (5.0, 2.0)], 5.0)


def test_random_series_agree_with_the_original_formula():
    rng = random.Random(7)
    for _ in range(300):
        start = rng.uniform(1, 500)
        inserted = [
            (rng.choice([0.0, round(rng.uniform(0, 720), 2)]), rng.uniform(1, 500))
            for _ in range(rng.randint(0, 6))
        ]
        series = Waypoints(start).with_points(inserted)
        for now in [0.0, 720.0, *(rng.uniform(0, 800) for _ in range(10))]:
            assert series.value_at(now) == pytest.approx(original(start, inserted, now), abs=1e-9)


def test_a_ramp_shown_exactly_changes_now_and_a_flat_stretch_at_its_end():
    series = Waypoints(10.0).with_points([(100.0, 10.0), (200.0, 20.0)])
    assert series.next_change(50.0) == 100.0  # flat 10 → 10 until the ramp begins
    assert series.next_change(150.0) == 150.0
    assert series.next_change(200.0) is None


def test_a_rounded_value_changes_when_the_ramp_crosses_a_rounding_boundary():
    stars = Waypoints(1847).with_point(587.31, 2000)
    now = 100.0
    shown = round(stars.value_at(now))
    due = stars.next_change(now, step=1)
    assert now < due
    assert round(stars.value_at(due - 1e-6)) == shown
    assert round(stars.value_at(due + 1e-6)) != shown


def test_a_shown_value_never_changes_before_next_change_says():
    rng = random.Random(11)
    for _ in range(100):
        series = Waypoints(rng.uniform(1, 100)).with_points(
            [(rng.uniform(1, 720), rng.uniform(1, 100)) for _ in range(rng.randint(1, 4))]
        )
        now = rng.uniform(0, 720)
        due = series.next_change(now, step=0.01)
        until = 800.0 if due is None else due
        shown = round(series.value_at(now), 2)
        samples = [now + (until - now) * k / 50 for k in range(50)]
        assert all(round(series.value_at(t), 2) == shown for t in samples if t < until)


def test_first_reach_is_the_exact_crossing_on_a_ramp_and_a_jumps_own_time():
    ramp = Waypoints(100.0).with_points([(100.0, 120.0), (200.0, 90.0)])
    assert ramp.first_reach(110.0, after=0.0, until=700.0, rising=True) == 50.0
    assert ramp.first_reach(95.0, after=0.0, until=700.0, rising=False) == pytest.approx(
        100.0 + 100.0 * 25.0 / 30.0
    )
    assert ramp.first_reach(95.0, after=0.0, until=150.0, rising=False) is None
    assert ramp.first_reach(105.0, after=120.0, until=700.0, rising=True) == 120.0  # already
    jump = Waypoints(100.0).with_points([(100.0, 100.0), (100.0, 130.0)])
    assert jump.first_reach(120.0, after=0.0, until=700.0, rising=True) == 100.0


def test_first_reach_agrees_with_a_fine_scan_of_random_series():
    rng = random.Random(11)
    for _ in range(200):
        series = Waypoints(rng.uniform(50, 150)).with_points(
            sorted((round(rng.uniform(0, 600), 1), rng.uniform(50, 150)) for _ in range(4))
        )
        level, rising = rng.uniform(60, 140), rng.random() < 0.5
        found = series.first_reach(level, after=0.0, until=600.0, rising=rising)

        def reached(v: float, level: float = level, rising: bool = rising) -> bool:
            return v >= level - 1e-9 if rising else v <= level + 1e-9

        scan = next((t / 10 for t in range(6001) if reached(series.value_at(t / 10))), None)
        if found is None:
            assert scan is None
        else:
            assert reached(series.value_at(found))
            assert scan is None or found <= scan + 1e-9
            assert all(not reached(series.value_at(t / 10)) for t in range(int(found * 10)))
