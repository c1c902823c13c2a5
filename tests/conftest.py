"""Shared fixtures: the `tally` test environment and a small named cast of runs."""

from __future__ import annotations

import contextlib
import os
import shutil
import urllib.request
from collections.abc import Iterator
from pathlib import Path
from typing import TYPE_CHECKING

import pytest
from django.conf import settings

from apps.scenarios.format import parse_scenario
from apps.tally.environment import TALLY, tally_scenario
from events import registry
from events.projection import clear_cache

if TYPE_CHECKING:  # imports Playwright when used, not when the suite starts
    from tests.chromium import KeptPlaywright, SharedChromium

REPO = Path(__file__).resolve().parents[1]
# The scenarios of ours the tests play and count: the session's copy of the files git tracks in
# scenarios/ (tests/settings.py), so a scenario authored in the admin never changes the suite.
OUR_SCENARIOS = Path(os.environ["SENTINEL_TEST_OUR_SCENARIOS"])
# The original benchmark's data, for the conformance tests (README, "Conformance tests").


def ours(environment: str | None = None) -> list:
    """Our scenarios as the server loads them (the session's copy), or one environment's: the
    counts a test expects, so that a new scenario changes no test."""
    from apps.scenarios.library import library

    found = library(OUR_SCENARIOS).by_id.values()
    return [s for s in found if environment in (None, s.environment)]


UPSTREAM = Path(os.environ.get("SENTINEL_UPSTREAM_DIR") or REPO.parent / "shared" / "upstream")
UPSTREAM_ABSENT = (
    f"original SentinelBench data absent: no {UPSTREAM} (set SENTINEL_UPSTREAM_DIR; "
    "README, Conformance tests)"
)


def pytest_configure(config):
    # The servers keep each thread's connection for good (sentinel_site/config.py). Threads of
    # the test process itself (consumers, tickers, workers started by tests) must not: on
    # PostgreSQL a connection left open in one of them would block dropping the test database.
    for database in settings.DATABASES.values():
        database["CONN_MAX_AGE"] = 0


SLOW_MARKERS = ("e2e", "browser", "slow")
# The suite runs on the production shape when it is given a database or a channel layer of its
# own (.ci/run's second leg); a `user_clone` test sets both aside and would repeat itself there,
# and a `production_shape` test, which starts the production shape itself, runs only there.
PRODUCTION_SHAPE = bool(os.environ.get("DATABASE_URL") or os.environ.get("REDIS_URL"))


def pytest_collection_modifyitems(items):
    """Tests that drive real browsers and subprocesses, or are slow in one process, first, in
    their random order (this runs after pytest-randomly's shuffle), then the rest in theirs. Most of their time is spent
    waiting on wall time (a clock at speed 4, a server's start), so begun early they overlap
    the quick tests in the other processes; drawn last, one minute-long test would be the only
    thing left running at the end while the other processes sat idle.

    Each leg skips what the other runs as it would itself:
    - on the production shape, the tests that run the README in a user's fresh clone: they drop
      the suite's settings and run on embedded defaults whatever the leg, so the embedded leg
      has already run exactly them;
    - on embedded defaults, the tests that start the production shape themselves (supervisord,
      two Daphnes, a ticker or Celery, their own Redis): on SQLite they would prove a shape
      nobody deploys, at a tenth of the leg's CPU; the production leg runs them on PostgreSQL."""
    items.sort(
        key=lambda item: (
            not any(item.get_closest_marker(m) for m in SLOW_MARKERS),
            item.get_closest_marker("user_clone") is None,  # the longest of all, first of all
        )
    )
    if PRODUCTION_SHAPE:
        elsewhere, reason = "user_clone", "a user's clone on embedded defaults: the embedded leg"
    else:
        elsewhere, reason = "production_shape", "the production shape on PostgreSQL: its leg"
    for item in items:
        if item.get_closest_marker(elsewhere):
            item.add_marker(pytest.mark.skip(reason=reason))


@pytest.fixture(scope="session")
def django_db_setup(django_db_setup, django_db_blocker):
    """pytest-django's test databases, whose sessions kept by other threads (CONN_MAX_AGE=None:
    servers, tickers, workers) are ended before they are dropped. PostgreSQL refuses to drop a
    database in use, and each run then left one behind, tens of MiB each."""
    yield
    from django.db import connections

    with django_db_blocker.unblock():
        for connection in connections.all(initialized_only=True):
            if connection.vendor == "postgresql":
                with connection.cursor() as cursor:
                    cursor.execute(
                        "SELECT pg_terminate_backend(pid) FROM pg_stat_activity "
                        "WHERE datname = current_database() AND pid <> pg_backend_pid()"
                    )


@pytest.fixture(scope="session")
def tally_environment():
    """The test-only `tally` environment (installed by tests/settings.py)."""
    return registry.get_environment(TALLY.name)


@pytest.fixture(autouse=True)
def fresh_projection_cache():
    # Test databases reuse primary keys across tests; a cache keyed by run id must not leak.
    clear_cache()
    yield
    clear_cache()


def _contents(root: Path) -> dict[Path, bytes]:
    return {path: path.read_bytes() for path in root.rglob("*") if path.is_file()}


_SHARED_COPY = _contents(OUR_SCENARIOS)


@pytest.fixture(autouse=True)
def shared_scenarios_untouched():
    """Fail the test that wrote into the session's shared copy of scenarios/ (an admin save
    through a server started before `own_scenarios`, say), and put the copy back: otherwise
    every later test in every process plays the edited file and fails far from the cause."""
    yield
    now = _contents(OUR_SCENARIOS)
    if now == _SHARED_COPY:
        return
    touched = sorted(str(p.relative_to(OUR_SCENARIOS)) for p in now.keys() ^ _SHARED_COPY.keys())
    touched += sorted(
        str(p.relative_to(OUR_SCENARIOS))
        for p in now.keys() & _SHARED_COPY.keys()
        if now[p] != _SHARED_COPY[p]
    )
    for path in now.keys() - _SHARED_COPY.keys():
        path.unlink()
    for path, content in _SHARED_COPY.items():
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(content)
    pytest.fail(
        f"this test wrote into the shared scenario copy {OUR_SCENARIOS} ({', '.join(touched)}); "
        "a test that edits scenarios asks for own_scenarios before live_site",
        pytrace=False,
    )


@pytest.fixture
def tally_spec():
    def make(**kwargs) -> dict:
        return parse_scenario(tally_scenario(**kwargs), source="tests").to_run_spec()

    return make


@pytest.fixture
def upstream_dir() -> Path:
    if not UPSTREAM.is_dir():
        pytest.skip(UPSTREAM_ABSENT)
    return UPSTREAM


@pytest.fixture
def running_ticker(settings, django_db_blocker):
    """The configured ticker backend, really running: in-process thread, or a Celery worker+beat.

    The Celery worker is a real subprocess pointed at the test database, so tests using this
    fixture must use `transaction=True` (the worker only sees committed rows).
    """
    if settings.SENTINEL_TICKER == "celery":
        from tests.celery_worker import celery_worker

        with celery_worker():
            yield "celery"
        return
    import threading

    from events.ticker import run_ticker_in_thread

    stop = threading.Event()
    thread = run_ticker_in_thread(stop)
    try:
        yield "inprocess"
    finally:
        stop.set()
        thread.join(timeout=5)


@pytest.fixture
def site_ticker(settings):
    """The ticker behind a `live_site`: Daphne's own in-process loop, or a real Celery worker.

    Not `running_ticker`: a second in-process ticker here would race Daphne's, and whatever it
    fired would be broadcast on this process's in-memory layer, which Daphne never hears.
    """
    if settings.SENTINEL_TICKER == "celery":
        from tests.celery_worker import celery_worker

        with celery_worker():
            yield "celery"
    else:
        yield "inprocess"


@pytest.fixture
def own_scenarios(settings, tmp_path) -> Path:
    """SENTINEL_SCENARIO_DIR: this test's own copy of scenarios/. An admin save is written
    through to its file (apps.scenarios.sync), so a test that edits a scenario must never edit
    the copy every other test of the session plays. Ask for it before `live_site`, whose
    server is started with the folder."""
    root = tmp_path / "scenarios"
    shutil.copytree(OUR_SCENARIOS, root)
    settings.SENTINEL_SCENARIO_DIR = root
    return root


class KeptSiteServer:
    """This test process's site server, kept from one `live_site` test to the next while they
    would start it the same way (its environment: database, settings module, scenario and
    catalog folders, every variable). Starting Daphne costs seconds; a test that changes what
    the server is started with (`own_scenarios`, a variable it sets) gets a new one, which is
    kept in turn."""

    # Set by pytest for each phase of each test: never a reason for another server.
    VOLATILE = frozenset({"PYTEST_CURRENT_TEST"})

    def __init__(self) -> None:
        self.key: tuple | None = None
        self.base_url = ""
        self._running: contextlib.ExitStack | None = None

    def serving(self) -> str:
        """The base URL of a server started as this test would start it, with no memory of
        earlier tests (tests/server_urls.py)."""
        from sentinel_site.site_server import child_environment, site_server

        key = tuple(
            sorted((k, v) for k, v in child_environment().items() if k not in self.VOLATILE)
        )
        if key == self.key:
            try:
                self._forget()
                return self.base_url
            except OSError:  # the kept server is gone (a crash, say): start another
                pass
        self.stop()
        running = contextlib.ExitStack()
        self.base_url = running.enter_context(
            site_server(
                extra_env={"SENTINEL_TEST_SHARED_SERVER": "1"},
                log_path=settings.BASE_DIR / "var" / "live-site.log",
            )
        )
        self._running, self.key = running, key
        self._forget()
        return self.base_url

    def _forget(self) -> None:
        from tests.server_urls import FORGET_PATH

        forgetting = urllib.request.Request(f"{self.base_url}/{FORGET_PATH}", method="POST")
        with urllib.request.urlopen(forgetting, timeout=30) as answer:
            assert answer.status == 204, f"the server did not forget earlier tests: {answer.status}"

    def stop(self) -> None:
        if self._running is not None:
            self._running.close()
        self._running, self.key = None, None


@pytest.fixture(scope="session")
def kept_site_server(django_db_setup) -> Iterator[KeptSiteServer]:
    """Stopped before the test database is dropped (PostgreSQL refuses while it is connected)."""
    kept = KeptSiteServer()
    try:
        yield kept
    finally:
        kept.stop()


@pytest.fixture
def live_site(transactional_db, site_ticker, kept_site_server):
    """Base URL of a real Daphne server (HTTP + websockets) serving the test database, with the
    configured ticker behind it, as in production: on the Celery leg a page would otherwise see
    a scenario event only when something reads the run (its next clock-driven push).

    The server outlives the test (`KeptSiteServer`): the database it serves is emptied after
    each test all the same (transactional), and what its process remembers is forgotten before
    the next one."""
    return kept_site_server.serving()


@pytest.fixture(scope="session")
def shared_chromium() -> Iterator[SharedChromium]:
    """Debian's Chromium (never `playwright install`), one per test process (tests/chromium.py),
    started when the process's first browser test asks for it."""
    from apps.browser_agent.browser import CHROMIUM
    from tests.chromium import SharedChromium

    executable = shutil.which("chromium") or CHROMIUM
    if not Path(executable).exists():
        pytest.fail("chromium is not installed: apt-get install -y chromium")
    shared = SharedChromium(executable)
    try:
        yield shared
    finally:
        shared.stop()


@pytest.fixture(scope="session")
def kept_playwright() -> Iterator[KeptPlaywright]:
    """Playwright's driver, one per test process (tests/chromium.py), lent to each browser test."""
    from tests.chromium import KeptPlaywright

    kept = KeptPlaywright()
    try:
        yield kept
    finally:
        kept.stop()


@pytest.fixture
def browser(shared_chromium, kept_playwright):
    """The process's Chromium, driven by the process's Playwright over the DevTools protocol;
    the contexts and pages the test opens are discarded after it."""
    from playwright.sync_api import expect

    from tests.browser_story import TIMEOUT_MS

    # `expect` has a ceiling of its own (5 s), which a page on a fully loaded machine can
    # miss: the same generous one as actions. It returns as soon as its condition holds.
    expect.set_options(timeout=TIMEOUT_MS)
    with kept_playwright.lent() as playwright:
        instance = playwright.chromium.connect_over_cdp(shared_chromium.endpoint)
        try:
            yield instance
        finally:
            instance.close()
