"""Fixtures for MicroMail: a run over the test cast with a virtual clock, and its URLs."""

from __future__ import annotations

import pytest
from django.test import Client

from events import lifecycle
from events.models import ClockMode
from tests.micromail.cast import CATALOG_DIR, mailbox_scenario


@pytest.fixture
def mail_run(db):
    """A run of the cast scenario, preloaded, its virtual clock at 0."""
    return lifecycle.create_run(
        mailbox_scenario(), clock_mode=ClockMode.VIRTUAL, catalog_dir=CATALOG_DIR
    )


@pytest.fixture
def browser() -> Client:
    return Client()


@pytest.fixture
def mail_url(mail_run):
    """`mail_url("?folder=junk")` → /r/<token>/micromail/?folder=junk."""

    def url(rest: str = "") -> str:
        return f"/r/{mail_run.token}/micromail/{rest}"

    return url
