"""The kit's line charts (apps/kit/charts.py): the 1D line at a run's start is a day's line, not a
lone point (finding: MicroHood's 1D chart was one vertical stroke over an empty box)."""

from __future__ import annotations

import re

from apps.kit.charts import HEIGHT, WIDTH, chart, earlier_today


def points(path: str) -> list[tuple[float, float]]:
    return [(float(x), float(y)) for x, y in re.findall(r"[ML](-?[\d.]+),(-?[\d.]+)", path)]


def price(t: float) -> float:
    return 100.0 + t / 100  # a dollar every hundred seconds


def test_at_the_start_the_1d_line_is_the_day_so_far_ending_at_the_start_value():
    line = chart("MRDN", "1D", price, now=0.0, span=720.0)
    drawn = points(line.path)
    assert len(drawn) > 30 and len({y for _, y in drawn}) > 10  # a line, not a point
    assert drawn[-1] == (WIDTH / 2, line.baseline_y)  # mid-chart, at the start value
    assert all(0 <= x <= WIDTH and 0 <= y <= HEIGHT for x, y in drawn)


def test_the_live_session_grows_across_the_right_half_and_ends_at_the_value_of_now():
    line = chart("MRDN", "1D", price, now=360.0, span=720.0)
    drawn = points(line.path)
    assert drawn[-1][0] == WIDTH * 3 / 4  # half the session gone
    assert line.last == price(360.0) and line.up
    assert len(earlier_today("MRDN", 100.0)) == len(drawn) - 90  # then 90 live samples


def test_the_day_before_the_run_is_the_same_on_every_page_and_differs_per_symbol():
    assert earlier_today("MRDN", 100.0) == earlier_today("MRDN", 100.0)
    assert earlier_today("MRDN", 100.0) != earlier_today("ORCH", 100.0)
    assert chart("MRDN", "1D", price, 0.0, 720.0) == chart("MRDN", "1D", price, 0.0, 720.0)
