"""Finding 11's benchmark exists and reports on both shapes (a tiny load: never a timed check)."""

from __future__ import annotations

import re
from io import StringIO

import pytest
from django.core.management import call_command

from sentinel_site.site_server import stop_process_group
from tests.production.redis_server import REDIS_SERVER, RedisServer

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.e2e]

LINE = re.compile(
    r"bench_scale: runs=3 rate=1 page_p95_ms=[\d.]+ lateness_p99_ms=(?:[\d.]+|nan) errors=0 "
    r"lost=0 rss_mib=[1-9]\d* requests=[1-9]\d* shape=(?P<shape>[\w-]+)"
)


def bench_scale(*args: str) -> str:
    out = StringIO()
    call_command(
        "bench_scale", "--runs", "3", "--seconds", "3", "--act-every", "1", *args,
        stdout=out, stderr=StringIO(),
    )  # fmt: skip
    return out.getvalue().strip().splitlines()[-1]


def test_bench_scale_loads_the_embedded_server():
    line = bench_scale()
    assert (found := LINE.fullmatch(line)), line
    assert found["shape"] == "embedded"


def test_bench_scale_loads_the_production_shape(settings):
    if not REDIS_SERVER.exists():
        pytest.skip(f"{REDIS_SERVER} is absent")
    redis = RedisServer()
    redis.start()
    settings.REDIS_URL = redis.url  # what the production shape's processes are given
    try:
        line = bench_scale("--processes", "1")
    finally:
        stop_process_group(redis.process)
    assert (found := LINE.fullmatch(line)), line
    assert found["shape"] == "production-1"
