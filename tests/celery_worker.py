"""Start a real Celery worker with embedded beat against the test database."""

from __future__ import annotations

import contextlib
import os
import subprocess
import sys
import time

from django.conf import settings

from sentinel_site.site_server import current_database_url, stop_process_group

REPO = settings.BASE_DIR


@contextlib.contextmanager
def celery_worker():
    env = dict(
        os.environ,
        DATABASE_URL=current_database_url(),
        SENTINEL_TICKER="celery",
        DJANGO_SETTINGS_MODULE=settings.SETTINGS_MODULE,
    )  # tests.settings: with tally
    (REPO / "var").mkdir(exist_ok=True)
    log = open(REPO / "var" / "celery-test.log", "ab")  # noqa: SIM115 - the worker's, till it exits
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
            str(REPO / "var" / "celerybeat-schedule"),
        ],
        cwd=REPO,
        env=env,
        stdout=log,
        stderr=subprocess.STDOUT,
        start_new_session=True,
    )
    try:
        time.sleep(4.0)  # worker and beat connect to the broker
        assert process.poll() is None, "the Celery worker exited at start; see var/celery-test.log"
        yield process
    finally:
        stop_process_group(process)
        log.close()
