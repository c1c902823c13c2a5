"""The uncertainty figures: Wilson intervals, bootstrap medians, pass@k / pass^k, and when two
result sets differ beyond the noise — against values worked out by hand or known tables."""

from __future__ import annotations

import pytest

from apps.bench.stats import (
    bootstrap_median,
    bootstrap_median_difference,
    newcombe_difference,
    pass_at_k,
    pass_hat_k,
    wilson,
)


def test_wilson_matches_the_textbook_values():
    # Newcombe (1998), table I: 81/263 → 0.2553–0.3662; 15/148 → 0.0624–0.1605.
    assert wilson(81, 263).low == pytest.approx(0.2553, abs=1e-4)
    assert wilson(81, 263).high == pytest.approx(0.3662, abs=1e-4)
    assert wilson(15, 148).low == pytest.approx(0.0624, abs=1e-4)
    assert wilson(15, 148).high == pytest.approx(0.1605, abs=1e-4)


def test_wilson_stays_inside_0_and_1_and_is_wide_for_few_tasks():
    none, every = wilson(0, 10), wilson(10, 10)
    assert none.low == 0.0 and 0.25 < none.high < 0.35
    assert every.high == 1.0 and 0.65 < every.low < 0.75
    # The example: a rate over 100 tasks is about ±10 points at 95 %.
    half = wilson(50, 100)
    assert 0.09 < (half.high - half.low) / 2 < 0.10
    assert wilson(0, 0) is None


def test_pass_at_k_and_pass_hat_k_are_the_unbiased_estimators():
    assert pass_at_k(3, 0, 3) == 0.0 and pass_hat_k(3, 0, 3) == 0.0
    assert pass_at_k(3, 3, 3) == 1.0 and pass_hat_k(3, 3, 3) == 1.0
    assert pass_at_k(3, 1, 3) == 1.0 and pass_hat_k(3, 1, 3) == 0.0
    assert pass_at_k(4, 2, 2) == pytest.approx(1 - 1 / 6)  # 1 − C(2,2)/C(4,2)
    assert pass_hat_k(4, 2, 2) == pytest.approx(1 / 6)  # C(2,2)/C(4,2)
    assert pass_at_k(5, 2, 1) == pytest.approx(0.4) == pass_hat_k(5, 2, 1)
    with pytest.raises(ValueError, match=r"k must be in 1\.\.3"):
        pass_at_k(3, 1, 4)


def test_bootstrap_median_is_reproducible_and_brackets_the_median():
    values = [float(v) for v in (3, 5, 8, 9, 12, 13, 15, 21, 30, 41)]
    first, again = bootstrap_median(values), bootstrap_median(values)
    assert first == again  # a fixed seed: the same results print the same interval
    assert first.low <= 12.5 <= first.high and first.low >= 3 and first.high <= 41
    assert bootstrap_median([4.0]) is None


def test_a_large_difference_is_beyond_the_noise_and_a_small_one_is_not():
    difference, interval = newcombe_difference(80, 100, 40, 100)
    assert difference == pytest.approx(0.4) and interval.low > 0
    # Newcombe (1998), table II, example (a): 56/70 − 48/80 → 0.0524–0.3339.
    _, example = newcombe_difference(56, 70, 48, 80)
    assert example.low == pytest.approx(0.0524, abs=1e-4)
    assert example.high == pytest.approx(0.3339, abs=1e-4)
    _, close = newcombe_difference(52, 100, 48, 100)
    assert close.contains(0.0)
    fast, slow = [1.0, 1.2, 0.9, 1.1, 1.0], [9.0, 8.5, 9.5, 10.0, 9.2]
    assert bootstrap_median_difference(fast, slow).high < 0
    assert bootstrap_median_difference(fast, fast).contains(0.0)
