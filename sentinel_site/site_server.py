"""A real site server in a subprocess: Daphne on a free port, stopped with its process group.

One implementation for everything that needs the whole site running beside it: the harness's
embedded server, `bench_pages`, `bench_live` and the live-site test fixtures. The subprocess
serves the database this process is configured with (or the one given), so runs created here
are visible there once committed; it inherits this process's scenario and catalog folders, so
both sides agree on the library.
"""

from __future__ import annotations

import contextlib
import os
import signal
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request
from collections.abc import Iterator
from pathlib import Path

from django.conf import settings
from django.db import connection


class ServerDidNotStart(RuntimeError):
    pass


def current_database_url() -> str:
    """This process's database (the test database under pytest) as a DATABASE_URL."""
    s = connection.settings_dict
    if s["ENGINE"].endswith("sqlite3"):
        name = str(s["NAME"])
        if name == ":memory:" or name.startswith("file:"):
            raise ServerDidNotStart("a server subprocess cannot share an in-memory SQLite database")
        return f"sqlite:///{name}"
    auth = s["USER"] + (f":{s['PASSWORD']}" if s["PASSWORD"] else "")
    return f"postgres://{auth}@{s['HOST'] or '127.0.0.1'}:{s['PORT'] or 5432}/{s['NAME']}"


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def child_environment(
    database_url: str | None = None, extra_env: dict[str, str] | None = None
) -> dict[str, str]:
    """The environment of a server started beside this process: its database, settings
    module, scenario and catalog folders, so both sides see the same runs and library."""
    return dict(
        os.environ,
        DATABASE_URL=database_url or current_database_url(),
        # This process's settings module (the test suite's adds the `tally` environment);
        # overridden settings (tests) do not know their module, the environment does.
        DJANGO_SETTINGS_MODULE=settings.SETTINGS_MODULE
        or os.environ.get("DJANGO_SETTINGS_MODULE", "sentinel_site.settings"),
        SENTINEL_SCENARIO_DIR=str(settings.SENTINEL_SCENARIO_DIR),
        SENTINEL_CATALOG_DIR=str(settings.SENTINEL_CATALOG_DIR),
        **(extra_env or {}),
    )


def wait_until_serving(
    process: subprocess.Popen, base_url: str, log_path: Path, startup_s: float
) -> None:
    deadline = time.monotonic() + startup_s
    while True:
        try:
            with urllib.request.urlopen(f"{base_url}/scenarios", timeout=2):
                return
        except urllib.error.HTTPError:
            return  # Django answered (the flat endpoints may be off): it serves
        except OSError:
            if process.poll() is not None or time.monotonic() > deadline:
                raise ServerDidNotStart(f"the site server did not start; see {log_path}") from None
            time.sleep(0.1)


def stop_process_group(process: subprocess.Popen) -> None:
    """SIGTERM the whole group (a server's own children go too), SIGKILL after 10 s."""
    with contextlib.suppress(ProcessLookupError):
        os.killpg(process.pid, signal.SIGTERM)
    try:
        process.wait(timeout=10)
    except subprocess.TimeoutExpired:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGKILL)
        process.wait(timeout=5)


@contextlib.contextmanager
def site_server(
    *,
    database_url: str | None = None,
    extra_env: dict[str, str] | None = None,
    log_path: Path | None = None,
    startup_s: float = 30.0,
    application: str = "sentinel_site.asgi:application",
) -> Iterator[str]:
    """Start Daphne serving `application` (the site, unless told), wait until it answers, yield
    its base URL (no trailing slash), stop it."""
    base = Path(settings.BASE_DIR)
    log_path = log_path or Path(settings.VAR_DIR) / "site-server.log"
    log_path.parent.mkdir(parents=True, exist_ok=True)
    env = child_environment(database_url, extra_env)
    port = free_port()
    with open(log_path, "ab") as log:
        process = subprocess.Popen(
            [
                sys.executable,
                "-m",
                "daphne",
                "-b",
                "127.0.0.1",
                "-p",
                str(port),
                application,
            ],
            cwd=base,
            env=env,
            stdout=log,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
        base_url = f"http://127.0.0.1:{port}"
        try:
            wait_until_serving(process, base_url, log_path, startup_s)
            yield base_url
        finally:
            stop_process_group(process)
