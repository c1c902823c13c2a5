"""Fixtures for MicroDin: a run over the cast with a virtual clock, and its URLs."""

from __future__ import annotations

import pytest

from tests.microdin.cast import CAST


@pytest.fixture
def din_run(db):
    """A run of the cast scenario, preloaded, its virtual clock at 0."""
    return CAST.start()


@pytest.fixture
def din_url(din_run):
    """`din_url("jobs/")` → /r/<token>/microdin/jobs/."""

    def url(rest: str = "") -> str:
        return f"/r/{din_run.token}/microdin/{rest}"

    return url
