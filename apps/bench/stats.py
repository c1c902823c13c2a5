"""The uncertainty of a benchmark's figures: pure functions, deterministic output.

- a rate's 95 % interval is Wilson's score interval (sound at 0 % and 100 % and for small n,
  where the normal approximation is not);
- a median's 95 % interval is a percentile bootstrap (2000 resamples, a fixed seed: the same
  results always print the same interval);
- pass@k is the chance that at least one of k trials of a task passes, pass^k that all k do,
  each estimated without bias from a task's n ≥ k trials of which c passed
  (1 − C(n−c, k)/C(n, k) and C(c, k)/C(n, k)), then averaged over tasks;
- two rates differ beyond the noise when Newcombe's interval for their difference (built from
  the two Wilson intervals) leaves out 0; two medians, when the bootstrap interval of their
  difference does.
"""

from __future__ import annotations

import math
import random
import statistics
from dataclasses import dataclass

Z95 = 1.959963984540054
BOOTSTRAP_RESAMPLES = 2000
BOOTSTRAP_SEED = 20260  # fixed: an interval is a function of the results, not of the moment


@dataclass(frozen=True)
class Interval:
    low: float
    high: float

    def contains(self, value: float) -> bool:
        return self.low <= value <= self.high


def wilson(passed: int, total: int, z: float = Z95) -> Interval | None:
    """Wilson's score interval for passed/total (None when there is nothing to count)."""
    if total <= 0:
        return None
    p = passed / total
    denominator = 1 + z * z / total
    centre = (p + z * z / (2 * total)) / denominator
    half = z * math.sqrt(p * (1 - p) / total + z * z / (4 * total * total)) / denominator
    # At 0 % and 100 % the bound is exactly 0 or 1 (the formula leaves a rounding error).
    low = 0.0 if passed == 0 else max(0.0, centre - half)
    high = 1.0 if passed == total else min(1.0, centre + half)
    return Interval(low, high)


def _resampled_medians(values: list[float], rng: random.Random, times: int) -> list[float]:
    n = len(values)
    return [statistics.median(rng.choices(values, k=n)) for _ in range(times)]


def _percentiles(samples: list[float]) -> Interval:
    ordered = sorted(samples)
    last = len(ordered) - 1
    return Interval(ordered[round(0.025 * last)], ordered[round(0.975 * last)])


def bootstrap_median(
    values: list[float], *, resamples: int = BOOTSTRAP_RESAMPLES, seed: int = BOOTSTRAP_SEED
) -> Interval | None:
    """Percentile-bootstrap 95 % interval of the median (None for fewer than 2 values)."""
    if len(values) < 2:
        return None
    return _percentiles(_resampled_medians(list(values), random.Random(seed), resamples))


def bootstrap_median_difference(
    a: list[float],
    b: list[float],
    *,
    resamples: int = BOOTSTRAP_RESAMPLES,
    seed: int = BOOTSTRAP_SEED,
) -> Interval | None:
    """95 % interval of median(a) − median(b), each set resampled on its own."""
    if len(a) < 2 or len(b) < 2:
        return None
    rng = random.Random(seed)
    left = _resampled_medians(list(a), rng, resamples)
    right = _resampled_medians(list(b), rng, resamples)
    return _percentiles([x - y for x, y in zip(left, right, strict=True)])


def newcombe_difference(
    passed_a: int, total_a: int, passed_b: int, total_b: int
) -> tuple[float, Interval] | None:
    """rate(a) − rate(b) and its 95 % interval (Newcombe's hybrid score method)."""
    wa, wb = wilson(passed_a, total_a), wilson(passed_b, total_b)
    if wa is None or wb is None:
        return None
    pa, pb = passed_a / total_a, passed_b / total_b
    difference = pa - pb
    low = difference - math.sqrt((pa - wa.low) ** 2 + (wb.high - pb) ** 2)
    high = difference + math.sqrt((wa.high - pa) ** 2 + (pb - wb.low) ** 2)
    return difference, Interval(low, high)


def pass_at_k(trials: int, passes: int, k: int) -> float:
    """Chance that at least one of k trials drawn from n passes (unbiased estimator)."""
    if not 0 < k <= trials:
        raise ValueError(f"k must be in 1..{trials}, got {k}")
    return 1.0 - math.comb(trials - passes, k) / math.comb(trials, k)


def pass_hat_k(trials: int, passes: int, k: int) -> float:
    """Chance that all k trials drawn from n pass (pass^k, unbiased estimator)."""
    if not 0 < k <= trials:
        raise ValueError(f"k must be in 1..{trials}, got {k}")
    return math.comb(passes, k) / math.comb(trials, k)
