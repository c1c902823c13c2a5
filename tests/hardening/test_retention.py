"""Runs are not kept forever (finding: runs could be created without limit and were never
purged): runs older than the retention age go, with their logs; harness results stay."""

from __future__ import annotations

import io
from datetime import timedelta

import pytest
from django.core.management import CommandError, call_command
from django.utils import timezone

from apps.bench.models import BenchmarkRun, TaskResult
from events import lifecycle, retention
from events.models import ClockMode, Event, Run

pytestmark = pytest.mark.django_db


def aged(run: Run, days: float) -> Run:
    Run.objects.filter(pk=run.pk).update(created_at=timezone.now() - timedelta(days=days))
    return run


def test_purge_runs_deletes_old_runs_and_their_logs_and_keeps_results(tally_spec):
    old = aged(lifecycle.create_run(tally_spec(), clock_mode=ClockMode.VIRTUAL), days=40)
    recent = aged(lifecycle.create_run(tally_spec(), clock_mode=ClockMode.VIRTUAL), days=3)
    benchmark = BenchmarkRun.objects.create(name="kept")
    result = TaskResult.objects.create(benchmark=benchmark, scenario_id="t", run=old, success=True)
    out = io.StringIO()
    call_command("purge_runs", stdout=out)  # the default age: 30 days
    assert "deleted 1 runs older than 30 days" in out.getvalue()
    assert list(Run.objects.values_list("pk", flat=True)) == [recent.pk]
    assert not Event.objects.filter(run_id=old.pk).exists()
    result.refresh_from_db()
    assert result.run is None and result.success is True


def test_purge_runs_takes_an_age(tally_spec):
    aged(lifecycle.create_run(tally_spec(), clock_mode=ClockMode.VIRTUAL), days=3)
    call_command("purge_runs", "--older-than-days", "2", stdout=io.StringIO())
    assert not Run.objects.exists()


def test_purge_runs_refuses_an_age_of_nothing():
    with pytest.raises(CommandError, match="--older-than-days must be more than 0"):
        call_command("purge_runs", "--older-than-days", "0")


def test_the_ticker_purges_once_a_day(tally_spec, settings, monkeypatch):
    monkeypatch.setattr(retention, "_last_purge", -retention.DAY_S)  # none yet in this process
    aged(lifecycle.create_run(tally_spec(), clock_mode=ClockMode.VIRTUAL), days=40)
    assert retention.purge_if_due() == 1
    aged(lifecycle.create_run(tally_spec(), clock_mode=ClockMode.VIRTUAL), days=40)
    assert retention.purge_if_due() is None  # not a day since the last
    settings.SENTINEL_RUN_RETENTION_DAYS = 0
    monkeypatch.setattr(retention, "_last_purge", -retention.DAY_S)
    assert retention.purge_if_due() is None  # 0: keep every run
    assert Run.objects.count() == 1
