"""Fixtures for MicroGram: a run over the cast with a virtual clock, and its URLs."""

from __future__ import annotations

import pytest

from tests.microgram.cast import CAST


@pytest.fixture
def gram_run(db):
    """A run of the cast scenario, preloaded, its virtual clock at 0."""
    return CAST.start()


@pytest.fixture
def gram_url(gram_run):
    """`gram_url("explore/")` → /r/<token>/microgram/explore/."""

    def url(rest: str = "") -> str:
        return f"/r/{gram_run.token}/microgram/{rest}"

    return url
