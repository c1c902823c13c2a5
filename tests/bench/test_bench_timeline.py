"""`manage.py bench_timeline` times the task timeline of a 10-minute task with 100 agent steps,
as the README quotes it, and leaves nothing behind."""

from __future__ import annotations

import re
from io import StringIO

import pytest
from django.core.management import call_command

from apps.bench.models import BenchmarkRun
from events.models import Run
from tests.bench.conftest import REPO

pytestmark = pytest.mark.django_db


LINE = re.compile(
    r"bench_timeline: render_ms_median=[\d.]+ render_ms_max=[\d.]+ steps=100 "
    r"entries=(\d+) target_ms=300"
)


def test_bench_timeline_renders_every_step_and_cleans_up():
    out = StringIO()
    call_command("bench_timeline", "--repeat", "2", stdout=out)
    line = out.getvalue().strip().splitlines()[-1]
    found = LINE.fullmatch(line)
    assert found, line
    # The README's figures are this command's lines.
    readme = (REPO / "README.md").read_text().splitlines()
    quoted = [text for text in readme if text.startswith("bench_timeline:")]
    assert quoted and all(LINE.fullmatch(text) for text in quoted)
    # 100 model calls, 40 judge questions, 100 page views, the world's events, the contact
    assert int(found.group(1)) > 240
    assert not Run.objects.exists() and not BenchmarkRun.objects.exists()
