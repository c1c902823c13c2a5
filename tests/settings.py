"""Settings for the test suite: the project's own, plus the test-only `tally` environment."""

import atexit
import os
import shutil
import subprocess
import tempfile
from pathlib import Path


# The scenarios the tests play: a throwaway copy of the files of scenarios/ that git tracks
# (every file where there is no git), made once per test session and shared with its worker
# processes through the environment. An admin edit is written through to its scenario file
# (apps.scenarios.sync), so no test ever edits the repository's own files; and a scenario a
# developer authored in the admin (a new file in scenarios/, not committed) is not in the copy,
# so it can never change what a test counts or plays.
def _our_scenarios(repo: Path) -> list[Path]:
    listed = subprocess.run(
        ["git", "ls-files", "-z", "scenarios"], cwd=repo, capture_output=True, check=False
    )
    if listed.returncode == 0 and listed.stdout:
        return [Path(name) for name in listed.stdout.decode().split("\0") if name]
    return [path.relative_to(repo) for path in (repo / "scenarios").rglob("*") if path.is_file()]


if "SENTINEL_TEST_OUR_SCENARIOS" not in os.environ:
    _repo = Path(__file__).resolve().parent.parent
    _copy = Path(tempfile.mkdtemp(prefix="sentinel-test-scenarios-"))
    for _file in _our_scenarios(_repo):
        if not (_repo / _file).is_file():
            continue  # deleted in the working tree: the tests play what is there
        (_copy / _file).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(_repo / _file, _copy / _file)
    os.environ["SENTINEL_TEST_OUR_SCENARIOS"] = str(_copy / "scenarios")
    atexit.register(shutil.rmtree, _copy, ignore_errors=True)
# What the site under test reads (servers the tests start inherit it): that copy, unless set.
os.environ.setdefault("SENTINEL_SCENARIO_DIR", os.environ["SENTINEL_TEST_OUR_SCENARIOS"])

# Parallel test processes (pytest-xdist: gw0, gw1, …) each get their own Redis database, so their
# channel layers and Celery queues never cross: run 1 of one process is not run 1 of another.
# Their SQL databases are already their own (the test database's name carries the process id).
# Done once, in the test process: servers and workers it starts inherit the URL as rewritten
# (and the worker's name), and must not move it again.
_worker = os.environ.get("PYTEST_XDIST_WORKER", "")
if (
    _worker.startswith("gw")
    and os.environ.get("REDIS_URL")
    and not os.environ.get("SENTINEL_TEST_REDIS_OWN")
):
    os.environ["SENTINEL_TEST_REDIS_OWN"] = "1"
    from urllib.parse import urlsplit, urlunsplit

    _url = urlsplit(os.environ["REDIS_URL"])
    _base = int(_url.path.strip("/") or 0)
    _db = (_base + 1 + int(_worker[2:])) % 16  # Redis has databases 0–15
    os.environ["REDIS_URL"] = urlunsplit(_url._replace(path=f"/{_db}"))

from sentinel_site.settings import *  # noqa: E402, F403

INSTALLED_APPS = [*INSTALLED_APPS, "apps.tally"]  # noqa: F405

# A site server the suite keeps between tests (`live_site`, tests/conftest.py) also answers
# tests/server_urls.py's URL, which makes it forget what earlier tests left in its memory.
if os.environ.get("SENTINEL_TEST_SHARED_SERVER") == "1":
    ROOT_URLCONF = "tests.server_urls"
