"""wait_for asks at the same simulated moments however long its looks take.

On a fast-forward run the clock runs at the speed factor while the agent brings its page up to
a skip's moment and reads it: a second or more on a loaded machine, a few milliseconds on an
idle one. The rate limit is counted from the model's answer timed from the look's moment, so
that time never shifts a later question (counted from the clock after the look, every question
came a second later per slow look, and a fast-forward run of ten at a time asked up to 8.5 s
after a live one). Pure: a fake skipping clock, a page that changes at given moments.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from itertools import pairwise

import pytest

from apps.browser_agent.waiting import wait_for

MINUTES = [60.0 * n for n in range(1, 11)]  # the shell's clock: a change every minute
TARGET_AT = 333.0
CONDITION = "the target arrives"


@dataclass
class SkippingFake:
    """A fast-forward clock: skips land where they are aimed, or at the page's next change."""

    changes: list[float]
    t: float = 0.0

    def now(self) -> float:
        return self.t

    def sleep(self, seconds: float) -> None:
        raise AssertionError("a fast-forward wait skips, it never sleeps")

    def skip_to(self, at: float, *, wake_at_change: bool) -> float | None:
        target = at
        if wake_at_change:
            upcoming = min((c for c in self.changes if c > self.t), default=math.inf)
            target = min(at, upcoming)
        self.t = max(self.t, target)
        return self.t


@dataclass
class SlowPage:
    """A page showing every change up to the clock; each read takes `work` simulated seconds."""

    clock: SkippingFake
    work: float
    looks: list[float] = field(default_factory=list)

    def markdown(self) -> str:
        self.looks.append(self.clock.t)
        shown = [f"{c:.0f}" for c in self.clock.changes if c <= self.clock.t]
        self.clock.t += self.work
        return "\n".join(["page", *(f"change {c}" for c in shown)]) + "\n"

    def reload(self) -> None:
        pass


@dataclass
class Judge:
    page: SlowPage
    asked_at: list[float] = field(default_factory=list)

    def __call__(self, condition: str, blocks: list[str]) -> tuple[bool, str]:
        self.asked_at.append(self.page.looks[-1])  # the moment of the look it was asked at
        met = any(f"+change {TARGET_AT:.0f}" in block for block in blocks)
        return met, "seen" if met else "not yet"


def questions(work: float) -> list[float]:
    clock = SkippingFake(sorted([*MINUTES, TARGET_AT]))
    page = SlowPage(clock, work)
    judge = Judge(page)
    result = wait_for(CONDITION, 600, page=page, judge=judge, clock=clock)
    assert result.met
    return judge.asked_at


@pytest.mark.parametrize("work", [1.3, 2.6, 5.0])
def test_slow_looks_ask_the_model_at_the_same_moments_as_quick_ones(work):
    quick = questions(0.02)

    assert questions(work) == quick
    # The rate limit still holds between questions, and the target is asked about.
    assert all(later - earlier >= 10 for earlier, later in pairwise(quick))
    assert quick[-1] >= TARGET_AT
