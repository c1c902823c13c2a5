"""Summary statistics for the benchmark commands' one-line figures."""

from __future__ import annotations


def percentile(values: list[float], q: float) -> float:
    """The q-th percentile (q in 0..100), interpolated between ranks; NaN when there are none."""
    if not values:
        return float("nan")
    ordered = sorted(values)
    rank = q / 100 * (len(ordered) - 1)
    low = int(rank)
    high = min(low + 1, len(ordered) - 1)
    return ordered[low] + (ordered[high] - ordered[low]) * (rank - low)
