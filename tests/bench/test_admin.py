"""Benchmark results can be browsed in the admin, with links to the graded runs."""

from __future__ import annotations

import pytest
from django.contrib.auth.models import User

from apps.bench.models import BenchmarkRun, TaskResult
from events import lifecycle

pytestmark = pytest.mark.django_db


def test_the_admin_lists_results_with_filters_and_run_links(client, tally_spec):
    run = lifecycle.create_run(tally_spec())
    benchmark = BenchmarkRun.objects.create(name="nightly", speed_factor=4.0)
    result = TaskResult.objects.create(
        benchmark=benchmark,
        scenario_id=run.scenario_id,
        environment="tally",
        category="passive-absolute",
        success=True,
        reaction_time=3.5,
        run=run,
    )
    client.force_login(User.objects.create_superuser("admin", "a@example.com", "pw"))
    listing = client.get("/admin/bench/taskresult/?success__exact=1")
    assert listing.status_code == 200
    assert f"/admin/events/run/{run.pk}/change/" in listing.content.decode()
    assert f"/admin/events/run/{run.pk}/task/" in listing.content.decode()  # its timeline
    assert client.get("/admin/bench/benchmarkrun/").status_code == 200
    detail = client.get(f"/admin/bench/benchmarkrun/{benchmark.pk}/change/")
    assert detail.status_code == 200 and run.scenario_id in detail.content.decode()
    assert client.get(f"/admin/bench/taskresult/{result.pk}/change/").status_code == 200
