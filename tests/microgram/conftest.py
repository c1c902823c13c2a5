"""Fixtures for MicroGram: a run over the cast with a virtual clock, and its URLs."""

from __future__ import annotations

import pytest

from events import lifecycle
from events.models import ClockMode
from tests.microgram.cast import cast_scenario


@pytest.fixture
def gram_run(db):
    """A run of the cast scenario, preloaded, its virtual clock at 0."""
    return lifecycle.create_run(cast_scenario(), clock_mode=ClockMode.VIRTUAL)


@pytest.fixture
def gram_url(gram_run):
    """`gram_url("explore/")` → /r/<token>/microgram/explore/."""

    def url(rest: str = "") -> str:
        return f"/r/{gram_run.token}/microgram/{rest}"

    return url
