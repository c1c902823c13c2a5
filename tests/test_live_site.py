"""The real server starts on the test database and serves a run created by the test."""

from __future__ import annotations

import json
import urllib.request

import pytest

pytestmark = pytest.mark.browser


def test_a_real_browser_reaches_a_run_contact_page(live_site, browser):
    request = urllib.request.Request(
        f"{live_site}/api/runs/",
        data=json.dumps(
            {"scenario": "micromail-sender-absolute-passive", "clock_mode": "virtual"}
        ).encode(),
        headers={"Content-Type": "application/json"},
        method="POST",
    )
    with urllib.request.urlopen(request, timeout=10) as response:
        run = json.load(response)
    page = browser.new_page()
    page.goto(f"{live_site}/r/{run['token']}/contact")
    assert page.title() == "Contact"
    assert page.locator("textarea[name=message]").count() == 1
