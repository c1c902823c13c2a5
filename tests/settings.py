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

from sentinel_site.settings import *  # noqa: F403

INSTALLED_APPS = [*INSTALLED_APPS, "apps.tally"]  # noqa: F405
