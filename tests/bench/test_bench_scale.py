"""Finding 11's benchmark exists and reports on both shapes (a tiny load: never a timed check)."""

from __future__ import annotations

import re
from io import StringIO

import pytest
from django.core.management import call_command

from apps.bench.management.commands.bench_scale import Command
from apps.micromail.bench import sample_pages
from apps.scenarios.library import scenario_library
from events import lifecycle
from events.commands import current_state
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


@pytest.mark.production_shape
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


@pytest.mark.django_db
def test_the_agents_never_load_a_page_of_an_item_their_run_retracts():
    """A recalled mail's reply form answers 404 once the mail is gone (as it should): it is not
    among the pages the load agents rotate through, which the mail's other pages still are."""
    mail = [s for s in scenario_library().values() if s.environment == "micromail"]
    (recalled,) = [s for s in mail if "recalled" in s.id]
    recall = next(e for e in recalled.to_run_spec()["events"] if e["type"] == "recall_email")
    gone = recall["payload"]["email_id"]
    command = Command()
    command.env = "micromail"
    run = lifecycle.create_run(recalled.to_run_spec(), speed_factor=4)
    lifecycle.advance(run, recall["time"] - 1)  # as bench_scale moves a run into its timeline
    at_start = [path for path in sample_pages(current_state(run))]
    assert any(gone in path for path in at_start)  # the mail is there, and its pages with it
    pages = command.lasting_pages(run)
    assert pages and not [path for path in pages if gone in path]
    assert set(pages) >= {path for path in at_start if "email=" not in path and "q=" not in path}
