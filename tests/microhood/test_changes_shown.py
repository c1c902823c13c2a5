"""A change is shown with one sign and one colour, in dollars and in percent alike.

Regression: MicroHood's crypto cards read "+$0.00 (−3.95 %)" in red — a coin under a dollar
moved by a fraction of a cent, rounded to "+$0.00" beside its percent.
"""

from __future__ import annotations

import pytest

from apps.microhood.screens import Change


@pytest.mark.parametrize(
    ("delta", "percent", "price", "shown"),
    [
        (-0.0033, -3.95, 0.0802, ("-$0.0033", "-3.95%", False)),  # a coin under a dollar
        (0.0012, 1.5, 0.0812, ("+$0.0012", "+1.50%", True)),
        (-0.004, -0.27, 1.48, ("-$0.0040", "-0.27%", False)),  # under a cent on a $1.48 coin
        (-12.5, -2.1, 583.0, ("-$12.50", "-2.10%", False)),
        (-0.001, -0.0004, 250.0, ("+$0.00", "+0.00%", True)),  # shown as zero: no sign, green
        (0.0, 0.0, 10.0, ("+$0.00", "+0.00%", True)),
    ],
)
def test_amount_percent_and_colour_agree(delta, percent, price, shown):
    change = Change.of(delta, percent, price)
    assert (change.amount, change.percent, change.up) == shown
