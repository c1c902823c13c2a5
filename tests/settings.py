"""Settings for the test suite: the project's own, plus the test-only `tally` environment."""

import atexit
import os
import shutil
import tempfile
from pathlib import Path

# An admin edit is written through to its scenario file (apps.scenarios.sync), so tests work
# on a throwaway copy of scenarios/, never the repository's own files. Set in the environment
# so that servers the tests start (site_server) share the same copy.
if "SENTINEL_SCENARIO_DIR" not in os.environ:
    _copy = Path(tempfile.mkdtemp(prefix="sentinel-test-scenarios-"))
    shutil.copytree(Path(__file__).resolve().parent.parent / "scenarios", _copy, dirs_exist_ok=True)
    os.environ["SENTINEL_SCENARIO_DIR"] = str(_copy)
    atexit.register(shutil.rmtree, _copy, ignore_errors=True)

# Parallel test processes (pytest-xdist: gw0, gw1, …) each get their own Redis database, so their
# channel layers and Celery queues never cross: run 1 of one process is not run 1 of another.
# Their SQL databases are already their own (the test database's name carries the process id).
_worker = os.environ.get("PYTEST_XDIST_WORKER", "")
if _worker.startswith("gw") and os.environ.get("REDIS_URL"):
    from urllib.parse import urlsplit, urlunsplit

    _url = urlsplit(os.environ["REDIS_URL"])
    _base = int(_url.path.strip("/") or 0)
    _db = (_base + 1 + int(_worker[2:])) % 16  # Redis has databases 0–15
    os.environ["REDIS_URL"] = urlunsplit(_url._replace(path=f"/{_db}"))

from sentinel_site.settings import *  # noqa: E402, F403

INSTALLED_APPS = [*INSTALLED_APPS, "apps.tally"]  # noqa: F405
