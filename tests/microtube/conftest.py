"""Fixtures for MicroTube: a run over the cast with a virtual clock, and its URLs."""

from __future__ import annotations

import pytest

from tests.microtube.cast import CAST


@pytest.fixture
def tube_run(db):
    """A run of the cast scenario, preloaded, its virtual clock at 0."""
    return CAST.start()


@pytest.fixture
def tube_url(tube_run):
    """`tube_url("feed/history")` → /r/<token>/microtube/feed/history."""

    def url(rest: str = "") -> str:
        return f"/r/{tube_run.token}/microtube/{rest}"

    return url
