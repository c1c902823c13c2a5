"""How a folder's condition times spread: targeted scenarios per 100-second bin.

The paper samples each task's condition time uniformly in [10, 600] s. Bunched condition
times let an agent that never looks score by acting or reporting at one fixed moment, so
`manage.py checkscenarios` prints the bins and fails when one holds more than a quarter of
the targeted (non-no-op) scenarios.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

from apps.scenarios.format import Scenario
from events.timing import MAX_CONDITION_AT

BIN_S = 100.0
MAX_BIN_SHARE = 0.25
# Below this many targeted scenarios a folder is a sample (tests, a draft), not a benchmark:
# its bins are printed, not judged.
MIN_JUDGED = 20


@dataclass(frozen=True)
class Bin:
    start: float
    end: float
    count: int
    share: float  # of the targeted scenarios
    closed: bool = False  # the last bin of [0, MAX_CONDITION_AT] includes its end

    @property
    def label(self) -> str:
        return f"[{self.start:3.0f}, {self.end:3.0f}{']' if self.closed else ')'} s"


@dataclass(frozen=True)
class Spread:
    bins: tuple[Bin, ...]
    targeted: int

    @property
    def judged(self) -> bool:
        return self.targeted >= MIN_JUDGED

    @property
    def crowded(self) -> tuple[Bin, ...]:
        """The bins above MAX_BIN_SHARE (none when the folder is too small to judge)."""
        if not self.judged:
            return ()
        return tuple(b for b in self.bins if b.share > MAX_BIN_SHARE)


def condition_spread(scenarios: Iterable[Scenario]) -> Spread:
    """Targeted scenarios per BIN_S-second bin of [0, MAX_CONDITION_AT] (600 s falls in the
    last bin), plus one bin per further BIN_S seconds a condition time reaches past it."""
    times = [s.condition_at for s in scenarios if not s.is_dev and s.condition_at is not None]
    last = max([MAX_CONDITION_AT, *times]) if times else MAX_CONDITION_AT
    count = max(1, math.ceil(last / BIN_S))
    counts = [0] * count
    regular = round(MAX_CONDITION_AT / BIN_S)
    for time in times:
        index = min(int(time // BIN_S), count - 1)
        if time == MAX_CONDITION_AT:
            index = regular - 1
        counts[index] += 1
    total = len(times)
    bins = tuple(
        Bin(
            start=i * BIN_S,
            end=(i + 1) * BIN_S,
            count=n,
            share=n / total if total else 0.0,
            closed=i == regular - 1,
        )
        for i, n in enumerate(counts)
    )
    return Spread(bins, total)
