"""Fixtures for MicroHub: a run over the cast with a virtual clock, and its URLs."""

from __future__ import annotations

import pytest

from tests.microhub.cast import CAST


@pytest.fixture
def hub_run(db):
    """A run of the cast scenario, preloaded, its virtual clock at 0."""
    return CAST.start()


@pytest.fixture
def hub_url(hub_run):
    """`hub_url("issues/")` → /r/<token>/microhub/issues/."""

    def url(rest: str = "") -> str:
        return f"/r/{hub_run.token}/microhub/{rest}"

    return url
