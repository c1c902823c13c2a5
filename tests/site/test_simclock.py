"""Elapsed-time texts of the kit (apps.kit.simclock): what they read, and that each
reads the same until the moment it says it next changes, and differently from then."""

from __future__ import annotations

import random

import pytest

from apps.kit.simclock import compact_ago, long_ago, units_changes_at

MIN, HOUR, DAY, WEEK = 60, 3600, 86400, 7 * 86400


@pytest.mark.parametrize(
    ("elapsed", "compact", "long"),
    [
        (0, "now", "just now"),
        (59.9, "now", "just now"),
        (60, "1m", "1 minute ago"),
        (5 * MIN + 30, "5m", "5 minutes ago"),
        (HOUR, "1h", "1 hour ago"),
        (2 * HOUR + 59 * MIN, "2h", "2 hours ago"),
        (3 * DAY, "3d", "3 days ago"),
        (WEEK, "1w", "1 week ago"),
        (12 * WEEK + DAY, "12w", "12 weeks ago"),
        (-30, "now", "just now"),  # a moment ahead of the clock reads as now
    ],
)
def test_what_they_read(elapsed, compact, long):
    assert compact_ago(1000.0, 1000.0 + elapsed) == compact
    assert long_ago(1000.0, 1000.0 + elapsed) == long


def test_each_text_holds_until_its_next_change_and_moves_then():
    rng = random.Random(7)
    for _ in range(500):
        at = rng.uniform(0, 10 * DAY)
        now = at + rng.choice(
            [rng.uniform(0, 2 * MIN), rng.uniform(0, 3 * DAY), rng.uniform(0, 9 * WEEK)]
        )
        change = units_changes_at(at, now)
        assert change > now
        for reader in (compact_ago, long_ago):
            assert reader(at, now) == reader(at, (now + change) / 2) == reader(at, change - 1e-3)
            assert reader(at, change) != reader(at, now)
