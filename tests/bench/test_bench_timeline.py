"""`manage.py bench_timeline` times the task timeline of a 10-minute task with 100 agent steps,
as the README quotes it, and leaves nothing behind."""

from __future__ import annotations

import re
from io import StringIO

import pytest
from django.core.management import call_command

from apps.bench.models import BenchmarkRun
from events.models import Run

pytestmark = pytest.mark.django_db


def test_bench_timeline_renders_every_step_and_cleans_up():
    out = StringIO()
    call_command("bench_timeline", "--repeat", "2", stdout=out)
    line = out.getvalue().strip().splitlines()[-1]
    found = re.fullmatch(
        r"bench_timeline: render_ms_median=[\d.]+ render_ms_max=[\d.]+ steps=100 "
        r"entries=(\d+) target_ms=300",
        line,
    )
    assert found, line
    # 100 model calls, 40 judge questions, 100 page views, the world's events, the contact
    assert int(found.group(1)) > 240
    assert not Run.objects.exists() and not BenchmarkRun.objects.exists()
