"""MicroDin in a real browser: a job is pushed into the open Jobs page, and the user applies.

The story: the self user opens the task URL of the Kubernetes scenario and goes to Jobs. The
harness moves the virtual clock to the moment CloudPeak posts its Infrastructure Engineer role;
the posting appears in the open list without a reload. The user opens it (the requirements name
Kubernetes only there), applies, and reports back. The grade sees exactly that one action.

Elements are found by role, label and text, so the test survives layout changes.
"""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import expect

from tests.browser_story import BrowserStory

pytestmark = pytest.mark.browser

SCENARIO = "microdin-kubernetes-absolute-active"
POSTED_AT = 71.0
TITLE = "Infrastructure Engineer"


def test_a_pushed_job_is_opened_and_applied_to(live_site, browser):
    story = BrowserStory.start(live_site, browser, SCENARIO)
    page = story.page

    primary = page.get_by_role("navigation", name="Primary")
    expect(primary.get_by_role("link", name=re.compile(r"^Home"))).to_be_visible()
    primary.get_by_role("link", name=re.compile(r"^Jobs")).click()
    jobs = page.get_by_role("list", name="Jobs")
    expect(jobs.get_by_role("link", name="Frontend Engineer")).to_be_visible()
    expect(jobs.get_by_role("link", name=TITLE)).to_have_count(0)
    story.watch_for_reload()

    story.advance(POSTED_AT)
    expect(jobs.get_by_role("link", name=TITLE)).to_be_visible()
    story.assert_not_reloaded()
    expect(page.get_by_text("Hands-on Kubernetes operations")).to_have_count(0)

    jobs.get_by_role("link", name=TITLE).click()
    expect(page.get_by_role("heading", level=2, name=TITLE)).to_be_visible()
    expect(page.get_by_text(re.compile("Hands-on Kubernetes operations"))).to_be_visible()
    page.get_by_role("button", name=re.compile(rf"^Apply to {TITLE}")).click()
    expect(page.get_by_text("Application sent to CloudPeak Hosting")).to_be_visible()
    expect(jobs.get_by_text("Applied")).to_have_count(1)

    assert story.report() == [("apply_job", {"job_id": "job-09"})]
