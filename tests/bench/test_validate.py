"""`bench validate` runs the four control agents on every scenario and checks the verdicts."""

from __future__ import annotations

import io
import re

import pytest
from django.core.management import call_command

pytestmark = pytest.mark.django_db(transaction=True)


def test_validate_proves_the_short_scenarios_solvable_and_not_trivially_passable(bench_scenarios):
    out = io.StringIO()
    call_command(
        "bench",
        "validate",
        "--speed-factor",
        "4",
        "--parallel",
        "10",
        "--reaction-window",
        "4",
        stdout=out,
    )
    lines = out.getvalue().splitlines()
    print(out.getvalue())
    assert re.fullmatch(
        r"bench_validate: scenarios=6 oracle=6/6 early_fail=5/5 never_ok=6/6 sleeper=\d/6 wall_s=[\d.]+",
        lines[-1],
    )
    assert float(lines[-1].rsplit("=", 1)[1]) < 40
