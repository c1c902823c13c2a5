"""The page and live-push benchmarks run for a registered environment, against a real server,
and name the valid environments when given another."""

from __future__ import annotations

import re
from io import StringIO

import pytest
from django.core.management import call_command
from django.core.management.base import CommandError
from django.db import connection

from events.models import Run

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.e2e]


def output(command: str, *args: str) -> list[str]:
    out = StringIO()
    call_command(command, *args, stdout=out, stderr=StringIO())
    return out.getvalue().strip().splitlines()


def run(command: str, *args: str) -> str:
    return output(command, *args)[-1]


def test_bench_live_measures_pushes_of_the_chosen_environment():
    line = run("bench_live", "--env", "micromail", "--seconds", "1", "--clients", "2")
    assert re.fullmatch(
        r"bench_live: push_p50_ms=[\d.]+ push_p99_ms=[\d.]+ messages=[1-9]\d*", line
    )


def test_bench_pages_times_the_chosen_environment():
    line = run("bench_pages", "--env", "micromail", "--seconds", "1", "--clients", "1")
    assert re.fullmatch(
        r"bench_pages: env=micromail p50_ms=[\d.]+ p95_ms=[\d.]+ requests=[1-9]\d*", line
    )


def test_bench_quiet_counts_pushes_per_minute_of_pages_with_nothing_due():
    # 64 simulated seconds at speed 4: the top bar's minute turns over once or twice.
    line = run("bench_quiet", "--env", "microlendar", "--seconds", "16", "--speed", "4")
    found = re.fullmatch(r"bench_quiet: max_pushes_per_min=([\d.]+) worst=microlendar/\S*", line)
    assert found and float(found.group(1)) <= 2.0, line


@pytest.mark.parametrize("command", ["bench_live", "bench_pages", "bench_quiet"])
def test_an_unknown_environment_is_named_with_the_valid_ones(command):
    with pytest.raises(CommandError, match=r"unknown --env 'nope'; valid: .*micromail"):
        run(command, "--env", "nope", "--seconds", "1")


def test_bench_protocol_ends_with_the_worst_figures_of_the_protocol():
    *_, floor, line = output("bench_protocol", "--quick", "--env", "micromail")
    # The machine's floor first: a request with nothing behind it costs something, never nothing.
    found = re.fullmatch(r"bench_protocol: floor_ms_median=([\d.]+) floor_ms_p99=([\d.]+)", floor)
    assert found and 0 < float(found.group(1)) <= float(found.group(2)), floor
    assert re.fullmatch(
        r"bench_protocol: reset_ms_median=[\d.]+ evaluate_ms_median=[\d.]+ "
        r"status_ms_p99=[\d.]+ pages_per_s_min=[\d.]+ push_cpu_ms=([\d.]+|nan) "
        r"rss_growth_mib=-?[\d.]+",
        line,
    )
    # Its dozens of runs went to a database of its own, not the one configured (SQLite).
    if connection.vendor == "sqlite":
        assert not Run.objects.exists()
