"""Settings for the test suite: the project's own, plus the test-only `tally` environment."""

from sentinel_site.settings import *  # noqa: F403

INSTALLED_APPS = [*INSTALLED_APPS, "apps.tally"]  # noqa: F405
