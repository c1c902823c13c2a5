"""A `BrowserStory` of a scenario written in the test itself (most browser tests keep their own
small scenario), not one of the library's.

`BrowserStory.start` names a library scenario (`{"scenario": id}`); the control API takes an
inline one as `scenario_json`, and everything after the run is created is the same story.

    story = inline_story(live_site, browser, scenario(), clock_mode="live", speed_factor=4.0)
"""

from __future__ import annotations

from typing import Any

from tests import control_api
from tests.browser_story import TIMEOUT_MS, VIEWPORT, BrowserStory


def inline_story(
    site: str, browser, scenario: dict, *, open_task: bool = True, **run: Any
) -> BrowserStory:
    """A run of `scenario` (virtual clock unless `run` says otherwise), its task URL opened."""
    created = control_api.call(
        site, "POST", "/api/runs/", {"scenario_json": scenario, "clock_mode": "virtual", **run}
    )
    page = browser.new_page(viewport=VIEWPORT)
    page.set_default_timeout(TIMEOUT_MS)
    if open_task:
        page.goto(created["task_url"])
    return BrowserStory(site, created, page)
