"""Fixtures for MicroMail: a run over the test cast with a virtual clock, and its URLs."""

from __future__ import annotations

import pytest
from django.test import Client

from tests.micromail.cast import CAST


@pytest.fixture
def mail_run(db):
    """A run of the cast scenario, preloaded, its virtual clock at 0."""
    return CAST.start()


@pytest.fixture
def browser() -> Client:
    return Client()


@pytest.fixture
def mail_url(mail_run):
    """`mail_url("?folder=junk")` → /r/<token>/micromail/?folder=junk."""

    def url(rest: str = "") -> str:
        return f"/r/{mail_run.token}/micromail/{rest}"

    return url
