"""Start a real Celery worker with embedded beat against the test database."""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

from django.db import connection

REPO = Path(__file__).resolve().parents[1]


def _database_url() -> str:
    s = connection.settings_dict
    auth = s["USER"] + (f":{s['PASSWORD']}" if s["PASSWORD"] else "")
    return f"postgres://{auth}@{s['HOST'] or '127.0.0.1'}:{s['PORT'] or 5432}/{s['NAME']}"


@contextlib.contextmanager
def celery_worker():
    env = dict(os.environ, DATABASE_URL=_database_url(), SENTINEL_TICKER="celery")
    log = open(REPO / "var" / "celery-test.log", "ab")
    process = subprocess.Popen(
        [sys.executable, "-m", "celery", "-A", "sentinel_site", "worker", "--beat", "--pool=threads",
         "--concurrency=4", "--loglevel=INFO", "-s", str(REPO / "var" / "celerybeat-schedule")],
        cwd=REPO, env=env, stdout=log, stderr=subprocess.STDOUT, start_new_session=True,
    )
    try:
        time.sleep(4.0)  # worker and beat connect to the broker
        assert process.poll() is None, "the Celery worker exited at start; see var/celery-test.log"
        yield process
    finally:
        os.killpg(process.pid, signal.SIGTERM)
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
        log.close()
