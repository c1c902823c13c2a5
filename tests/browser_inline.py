"""`BrowserStory` over a scenario written in the test itself (sent inline as `scenario_json`)
rather than one of the library: `BrowserStory.start` takes a library id only."""

from __future__ import annotations

from typing import Any

from tests import control_api
from tests.browser_story import TIMEOUT_MS, VIEWPORT, BrowserStory


def start_inline(site: str, browser, scenario: dict, **run: Any) -> BrowserStory:
    """A virtual-clock run of the inline `scenario` on the live site, its task URL opened."""
    body = {"scenario_json": scenario, "clock_mode": "virtual", **run}
    created = control_api.call(site, "POST", "/api/runs/", body)
    page = browser.new_page(viewport=VIEWPORT)
    page.set_default_timeout(TIMEOUT_MS)
    page.goto(created["task_url"])
    return BrowserStory(site, created, page)
