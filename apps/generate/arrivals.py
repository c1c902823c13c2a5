"""When things arrive: a seeded, non-uniform arrival process per environment.

A real inbox does not receive mail at uniformly random moments, and a chat does not either.
Each environment's process is an intensity profile over the run (relative arrival rate at each
simulated second, `profile`) and a clustering rule (`burst`: how many arrivals follow one, and
how far apart), sampled from one `random.Random`:

| environment | process |
|---|---|
| micromail | morning mail: the rate falls from 2.2x to 0.8x over the run; a mail draws a reply 30-120 s later one time in three |
| microchat | bursts: a conversation starts, then 1-4 more messages follow 3-25 s apart |
| microdin | lunchtime scrolling: the rate peaks mid-run (1.8x at 300 s), 1-2 follow-ups 20-60 s apart |
| microlendar | sparse, steady: flat rate, no clustering (invitations come one at a time) |
| microscholar | alert digests: papers come in batches of 2-4, 5-15 s apart |
| microfy, microtube, microgram | evening feed: the rate climbs from 0.6x to 1.9x; uploads draw comments/likes 10-40 s later |
| microhood | market hours: news in steady drift with jumps (a rate of 1x, 2.5x around two jump times) |
| microhub | pushes: every push draws 1-3 follow-ups (issues, runs) 15-90 s later |

A process gives background arrival times (`arrival_times`) and one condition time
(`condition_time`): the trigger arrives by the same process, restricted to [10, 574] s, the
window in which a contact can still be timely (README "What an agent can reach"), and to one of
six equal strata of it, taken in turn by an environment's scenarios, so that condition times spread
over the whole window as the paper's do (no 100-second bin above a quarter, `checkscenarios`)
while within a stratum they follow the environment's profile.
"""

from __future__ import annotations

import math
import random
from collections.abc import Callable
from dataclasses import dataclass

CONDITION_WINDOW = (10.0, 574.0)  # simulated seconds: where a generated trigger may arrive
GRID_S = 1.0  # the profile is sampled every simulated second
STRATA = 6  # parts of CONDITION_WINDOW an environment's scenarios take in turn


@dataclass(frozen=True)
class Burst:
    """After an arrival, `extra` more (drawn uniformly in its range) at `gap` seconds apart."""

    extra: tuple[int, int]
    gap: tuple[float, float]
    chance: float = 1.0  # the share of arrivals that draw followers at all


@dataclass(frozen=True)
class Process:
    description: str
    profile: Callable[[float], float]  # simulated second -> relative rate (> 0)
    burst: Burst | None = None

    def _draw(self, rng: random.Random, low: float, high: float) -> float:
        """One time in [low, high] with density proportional to the profile."""
        grid = [low + i * GRID_S for i in range(max(1, int((high - low) / GRID_S)))]
        weights = [self.profile(t) for t in grid]
        start = rng.choices(grid, weights=weights)[0]
        return min(high, start + rng.random() * GRID_S)

    def condition_time(self, rng: random.Random, stratum: int | None = None) -> float:
        """A trigger's arrival in CONDITION_WINDOW, or in its `stratum`-th of STRATA equal
        parts: the generator gives an environment's successive scenarios successive strata (in
        an order of its own), so condition times cover the window whatever the profile."""
        low, high = CONDITION_WINDOW
        if stratum is not None:
            width = (high - low) / STRATA
            low, high = low + stratum * width, low + (stratum + 1) * width
        return round(self._draw(rng, low, high), 2)

    def arrival_times(self, rng: random.Random, count: int, low: float, high: float) -> list[float]:
        """`count` sorted times in (low, high): leaders drawn by the profile, followers by the
        burst rule, until there are enough."""
        times: list[float] = []
        while len(times) < count:
            leader = self._draw(rng, low, high)
            times.append(leader)
            if self.burst and rng.random() < self.burst.chance:
                at = leader
                for _ in range(rng.randint(*self.burst.extra)):
                    at += rng.uniform(*self.burst.gap)
                    if at < high:
                        times.append(at)
        return sorted(round(t, 2) for t in times[:count])


def _ramp(start: float, end: float, span: float = 720.0) -> Callable[[float], float]:
    return lambda t: start + (end - start) * min(1.0, t / span)


def _peak(height: float, at: float, width: float) -> Callable[[float], float]:
    return lambda t: 1.0 + (height - 1.0) * math.exp(-(((t - at) / width) ** 2))


def _jumps(*times: float) -> Callable[[float], float]:
    return lambda t: 1.0 + 1.5 * sum(math.exp(-(((t - j) / 25.0) ** 2)) for j in times)


FEED = Process(
    "evening feed: rate climbs 0.6x -> 1.9x; uploads draw reactions 10-40 s later",
    _ramp(0.6, 1.9),
    Burst((1, 2), (10.0, 40.0), chance=0.5),
)

PROCESSES: dict[str, Process] = {
    "micromail": Process(
        "morning mail: rate falls 2.2x -> 0.8x; one mail in three draws a reply 30-120 s later",
        _ramp(2.2, 0.8),
        Burst((1, 1), (30.0, 120.0), chance=1 / 3),
    ),
    "microchat": Process(
        "bursts: a conversation starts, 1-4 more messages follow 3-25 s apart",
        lambda t: 1.0,
        Burst((1, 4), (3.0, 25.0)),
    ),
    "microdin": Process(
        "lunchtime scrolling: rate peaks at 1.8x mid-run; 1-2 follow-ups 20-60 s apart",
        _peak(1.8, 300.0, 150.0),
        Burst((1, 2), (20.0, 60.0), chance=0.4),
    ),
    "microlendar": Process("sparse and steady: flat rate, one at a time", lambda t: 1.0),
    "microscholar": Process(
        "alert digests: batches of 2-4 papers 5-15 s apart",
        lambda t: 1.0,
        Burst((1, 3), (5.0, 15.0)),
    ),
    "microfy": FEED,
    "microtube": FEED,
    "microgram": FEED,
    "microhood": Process(
        "market hours: steady drift with two jumps (2.5x around 140 s and 420 s)",
        _jumps(140.0, 420.0),
    ),
    "microhub": Process(
        "pushes: every push draws 1-3 follow-ups 15-90 s later",
        lambda t: 1.0,
        Burst((1, 3), (15.0, 90.0)),
    ),
}

STEADY = Process("steady: flat rate, one at a time", lambda t: 1.0)


def process_for(environment: str) -> Process:
    return PROCESSES.get(environment, STEADY)
