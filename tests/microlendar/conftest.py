"""Fixtures for MicroLendar: runs over our catalog (fixtures/) with a virtual clock."""

from __future__ import annotations

import pytest
from django.test import Client

from tests.microlendar.cast import CAST


@pytest.fixture
def calendar_run(db):
    """A run of the cast scenario: preloaded at t=0 on Thu 18 Sep 2025, its virtual clock at 0."""
    return CAST.start()


@pytest.fixture
def browser() -> Client:
    return Client()


@pytest.fixture
def cal_url(calendar_run):
    """`cal_url("?view=week")` → /r/<token>/microlendar/?view=week."""

    def url(rest: str = "") -> str:
        return f"/r/{calendar_run.token}/microlendar/{rest}"

    return url
