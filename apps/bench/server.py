"""The embedded server: Daphne in a subprocess on the configured database, on a free port.

Used when the config gives no server_url. The subprocess inherits the scenario and catalog
folders of this process, so the harness and the server agree on the library.
"""

from __future__ import annotations

import contextlib
import os
import signal
import socket
import subprocess
import sys
import time
import urllib.request
from collections.abc import Iterator
from pathlib import Path

from django.conf import settings
from django.db import connection

from apps.bench.client import HarnessError


def database_url() -> str:
    """The database this process uses (the test database under pytest), as a URL."""
    s = connection.settings_dict
    if s["ENGINE"].endswith("sqlite3"):
        name = str(s["NAME"])
        if name == ":memory:" or name.startswith("file:"):
            raise HarnessError("the embedded server needs a file or PostgreSQL database, not in-memory SQLite")
        return f"sqlite:///{name}"
    auth = s["USER"] + (f":{s['PASSWORD']}" if s["PASSWORD"] else "")
    return f"postgres://{auth}@{s['HOST'] or '127.0.0.1'}:{s['PORT'] or 5432}/{s['NAME']}"


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


@contextlib.contextmanager
def embedded_server(*, log_path: Path | None = None, startup_s: float = 30.0) -> Iterator[str]:
    """Start Daphne, wait until it answers, yield its base URL, stop it (whole process group)."""
    base = Path(settings.BASE_DIR)
    port = free_port()
    env = dict(
        os.environ,
        DATABASE_URL=database_url(),
        SENTINEL_SCENARIO_DIR=str(settings.SENTINEL_SCENARIO_DIR),
        SENTINEL_CATALOG_DIR=str(settings.SENTINEL_CATALOG_DIR),
    )
    log_path = log_path or base / "var" / "bench-server.log"
    log_path.parent.mkdir(parents=True, exist_ok=True)
    log = open(log_path, "ab")
    process = subprocess.Popen(
        [sys.executable, "-m", "daphne", "-b", "127.0.0.1", "-p", str(port), "sentinel_site.asgi:application"],
        cwd=base, env=env, stdout=log, stderr=subprocess.STDOUT, start_new_session=True,
    )
    base_url = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + startup_s
        while True:
            try:
                with urllib.request.urlopen(f"{base_url}/scenarios", timeout=2):
                    break
            except OSError:
                if process.poll() is not None or time.monotonic() > deadline:
                    raise HarnessError(f"the embedded server did not start; see {log_path}") from None
                time.sleep(0.1)
        yield base_url
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGTERM)
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(process.pid, signal.SIGKILL)
            process.wait()
        log.close()
