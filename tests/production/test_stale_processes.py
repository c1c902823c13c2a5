"""Nothing of a production set outlives its supervisord, and a new start clears what an older
one left (finding: after `kill -9` of supervisord its children ran on unsupervised, holding the
port, and a new `./dev production` failed to bind it)."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path
from urllib.parse import urlsplit

import pytest

from sentinel_site.production import (
    REPO,
    Shape,
    production_site,
    stop_stale,
)
from sentinel_site.site_server import child_environment

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.e2e]

PATIENCE_S = 60.0


def gone(pid: int) -> bool:
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return True
    return stat.rsplit(")", 1)[1].split()[0] == "Z"  # a zombie has exited


def wait_until_gone(pids: list[int]) -> None:
    deadline = time.monotonic() + PATIENCE_S
    while not all(gone(pid) for pid in pids):
        assert time.monotonic() < deadline, f"still running: {[p for p in pids if not gone(p)]}"
        time.sleep(0.1)


def test_killing_supervisord_takes_its_children_and_frees_the_port(django_db_blocker, redis_server):
    with django_db_blocker.unblock(), production_site(1, redis_url=redis_server.url) as site:
        children = [pid for pid in site.pids() if pid != site.supervisord.pid]
        assert len(children) == len(site.shape.programs)
        os.kill(site.supervisord.pid, signal.SIGKILL)
        site.supervisord.wait(timeout=PATIENCE_S)
        wait_until_gone(children)
        port = urlsplit(site.base_url).port
        with socket.socket() as sock:  # a new start could bind it
            sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            sock.bind(("127.0.0.1", port))


def test_a_new_start_stops_what_an_older_one_left_and_nothing_else(tmp_path):
    """Only processes carrying this shape's mark: another shape's, and a look-alike started from
    this checkout without one (a test's Celery worker or ticker: CI lost one to a parallel test
    that matched by command line), run on."""
    shape = Shape(run_dir=tmp_path / "production")
    ticker = [sys.executable, "-m", "sentinel_site.production", "ticker"]
    env = child_environment()  # real tickers, on the test database (no live runs in it)
    left = subprocess.Popen(ticker, cwd=REPO, env={**env, **shape.environment})
    other_shape = Shape(run_dir=tmp_path / "other")
    elsewhere = subprocess.Popen(ticker, cwd=REPO, env={**env, **other_shape.environment})
    look_alike = subprocess.Popen(ticker, cwd=REPO, env=env)
    processes = (left, elsewhere, look_alike)
    try:
        stopped = stop_stale(shape)
        assert stopped == [left.pid]
        left.wait(timeout=PATIENCE_S)
        assert elsewhere.poll() is None and look_alike.poll() is None
    finally:
        for process in processes:
            process.kill()
            process.wait()
