"""Fixtures for the first-hour tests: a scenario folder of our own, and the API client."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from rest_framework.test import APIClient

from tests.conftest import OUR_SCENARIOS

INBOX = "micromail/inbox-relative-passive.json"
JUNK = "micromail/junk-relative-passive.json"


@pytest.fixture
def api() -> APIClient:
    return APIClient()


@pytest.fixture
def scenario_dir(settings, tmp_path) -> Path:
    """SENTINEL_SCENARIO_DIR: a copy of our MicroMail scenarios, free to edit and break."""
    root = tmp_path / "scenarios"
    shutil.copytree(OUR_SCENARIOS / "micromail", root / "micromail")
    settings.SENTINEL_SCENARIO_DIR = root
    return root
