"""The production shape under test: its own Redis (never the shared one) and a supervised set.

Both live for the module: starting four Python processes under supervisord costs seconds, and
each test leaves the set healed (that is what they check).
"""

from __future__ import annotations

import pytest

from sentinel_site.site_server import stop_process_group
from tests.production.redis_server import REDIS_SERVER, RedisServer


@pytest.fixture(scope="module")
def redis_server():
    if not REDIS_SERVER.exists():
        pytest.skip(f"{REDIS_SERVER} is absent")
    server = RedisServer()
    server.start()
    try:
        yield server
    finally:
        if server.process is not None:
            stop_process_group(server.process)


@pytest.fixture(scope="module", params=["process", "celery"])
def production(request, django_db_setup, django_db_blocker, redis_server):
    """Two Daphne processes and the ticker (its own process, or Celery worker + beat) under
    supervisord, on the test database."""
    from sentinel_site.production import production_site

    with (
        django_db_blocker.unblock(),
        production_site(2, ticker=request.param, redis_url=redis_server.url) as site,
    ):
        yield site
