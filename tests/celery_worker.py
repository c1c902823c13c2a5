"""Start a real Celery worker with embedded beat against the test database."""

from __future__ import annotations

import contextlib
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from django.conf import settings

from sentinel_site.site_server import child_environment, stop_process_group

REPO = settings.BASE_DIR


READY_WITHIN_S = 90.0  # a generous ceiling for a loaded machine; an idle one answers in ~2 s


def wait_until_ready(process: subprocess.Popen) -> None:
    """Until the worker answers a ping over the broker (it consumes tasks from then on), or it
    exited (its log says why)."""
    from sentinel_site.celery import app

    deadline = time.monotonic() + READY_WITHIN_S
    while time.monotonic() < deadline:
        assert process.poll() is None, "the Celery worker exited at start; see var/celery-test.log"
        if app.control.ping(timeout=0.5):
            return
    raise AssertionError(f"the Celery worker did not answer within {READY_WITHIN_S:g} s")


@contextlib.contextmanager
def celery_worker():
    # As a test's server sees it: the test database, tests.settings (with tally), and the
    # scenario folder the test set (own_scenarios) — so the worker fires what the pages show.
    env = child_environment(extra_env={"SENTINEL_TICKER": "celery"})
    (REPO / "var").mkdir(exist_ok=True)
    log = open(REPO / "var" / "celery-test.log", "ab")  # noqa: SIM115 - the worker's, till it exits
    # Beat's schedule of its own: workers of parallel test processes never share one.
    schedule_dir = tempfile.mkdtemp(prefix="sentinel-beat-")
    process = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "celery",
            "-A",
            "sentinel_site",
            "worker",
            "--beat",
            "--pool=threads",
            "--concurrency=4",
            "--loglevel=INFO",
            "-s",
            str(Path(schedule_dir) / "celerybeat-schedule"),
        ],
        cwd=REPO,
        env=env,
        stdout=log,
        stderr=subprocess.STDOUT,
        start_new_session=True,
    )
    try:
        wait_until_ready(process)
        yield process
    finally:
        stop_process_group(process)
        log.close()
        shutil.rmtree(schedule_dir, ignore_errors=True)
