"""One shape for every environment's browser story: start a scenario's run on the live site,
open its task URL in Chromium at 1280×800, move its clock, check a pushed item arrived without a
reload, report through the contact page and read the verdict and the logged actions.

    def test_…(live_site, browser):
        story = BrowserStory.start(live_site, browser, "microdin-kubernetes-absolute-active")
        story.page.get_by_role(…).click()
        story.watch_for_reload()
        story.advance(71.0)
        expect(…).to_be_visible()
        story.assert_not_reloaded()
        …
        assert story.report() == [("apply_job", {"job_id": "job-09"})]

Waits are Playwright's own expectations (a condition with a ceiling), never a fixed sleep.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from tests import control_api

VIEWPORT = {"width": 1280, "height": 800}
# Generous: on a fully loaded 2-core machine a first render can take seconds. Expectations
# return as soon as their condition holds, so the ceiling costs nothing when the machine is idle.
TIMEOUT_MS = 30_000


@dataclass
class BrowserStory:
    site: str  # the live site's base URL
    run: dict  # the run as the control API created it (id, task_url, contact_url, …)
    page: Any  # a Playwright page

    @classmethod
    def start(
        cls, site: str, browser, scenario: str | dict, *, open_task: bool = True, **run: Any
    ) -> BrowserStory:
        """A run of `scenario` — a library scenario's id, or a scenario written in the test —
        on the live site (virtual clock unless `run` says otherwise), its task URL opened."""
        chosen = (
            {"scenario": scenario} if isinstance(scenario, str) else {"scenario_json": scenario}
        )
        created = control_api.call(
            site, "POST", "/api/runs/", {**chosen, "clock_mode": "virtual", **run}
        )
        page = browser.new_page(viewport=VIEWPORT)
        page.set_default_timeout(TIMEOUT_MS)
        story = cls(site, created, page)
        if open_task:
            page.goto(created["task_url"])
        return story

    def api(self, method: str, path: str, body: dict | None = None):
        return control_api.call(self.site, method, path, body)

    @classmethod
    def before_the_clock(cls, site: str, browser, scenario: str | dict, **run: Any) -> BrowserStory:
        """A run of `scenario` with its start page open and its clock not started (`start_clock`
        starts it). What a page shows before anything has arrived can then be checked on any
        machine: a live clock started by the task URL delivered first whenever a loaded machine
        took longer to render the page than the scenario took to its first arrival."""
        story = cls.start(site, browser, scenario, open_task=False, **run)
        story.page.goto(f"{site}/r/{story.run['token']}/{story.run['environment']}")
        return story

    def start_clock(self) -> None:
        """Start the run's clock as the agent's first visit does — a GET of its task URL — but
        without following it, so the open page stays as it is."""
        response = self.page.request.get(self.run["task_url"], max_redirects=0)
        assert response.status == 302, f"the task URL answered {response.status}"

    def watch_for_reload(self) -> None:
        """Mark the page once its live client is up: a reload would lose the mark."""
        self.page.wait_for_function("() => document.getElementById('sentinel-live')")
        self.page.evaluate("window.sentinelLoadedOnce = true")

    def assert_not_reloaded(self) -> None:
        assert self.page.evaluate("window.sentinelLoadedOnce") is True, "the page reloaded"

    def advance(self, time: float) -> None:
        """Move the run's virtual clock to `time` (scenario seconds)."""
        self.api("POST", f"/api/runs/{self.run['id']}/advance/", {"time": time})

    def actions(self) -> list[tuple[str, dict]]:
        """The agent actions logged so far, in order, as (type, payload)."""
        logged = self.api("GET", f"/api/runs/{self.run['id']}/events/")
        return [(e["type"], e["payload"]) for e in logged if e["kind"] == "action"]

    def report(self, *, success: bool = True) -> list[tuple[str, dict]]:
        """Report through the contact page, check the verdict, and return the logged actions."""
        self.page.goto(self.run["contact_url"])
        verdict = self.api("POST", f"/api/runs/{self.run['id']}/evaluate/")
        assert verdict["success"] is success, verdict["detail"]
        return self.actions()


def admin_page(browser, site: str, username: str, password: str):
    """A new page logged in to the admin as `username`, with the story's timeout."""
    page = browser.new_page()
    page.set_default_timeout(TIMEOUT_MS)
    page.goto(f"{site}/admin/login/")
    page.fill("#id_username", username)
    page.fill("#id_password", password)
    page.click("input[type=submit]")
    return page
