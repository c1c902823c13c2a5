"""The real server starts on the test database and serves a run created by the test."""

from __future__ import annotations

import pytest

from tests import control_api

pytestmark = pytest.mark.browser


def test_a_real_browser_reaches_a_run_contact_page(live_site, browser):
    run = control_api.post(
        live_site,
        "/api/runs/",
        {"scenario": "micromail-sender-absolute-passive", "clock_mode": "virtual"},
    )
    page = browser.new_page()
    page.goto(f"{live_site}/r/{run['token']}/contact")
    assert page.title() == "Contact"
    assert page.locator("textarea[name=message]").count() == 1
