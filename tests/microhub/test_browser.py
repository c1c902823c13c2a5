"""MicroHub in a real browser: a filed issue is pushed into the open Issues tab, and the user
comments on it.

The story (our compliance scenario): the self user opens the task URL and goes to Issues. The
harness moves the virtual clock to the moment the audit-log export issue is filed; it appears
in the open list without a reload, and the open-issue counter in the tab row goes up. The user
opens it (the word "compliance" is in its description only), comments, and reports back. The
grade sees exactly those actions: the implicit view of the issue and the comment.

Elements are found by role, label and text, so the test survives layout changes.
"""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import expect

from tests.browser_story import BrowserStory

pytestmark = pytest.mark.browser

SCENARIO = "microhub-compliance-absolute-active"
FILED_AT = 287.16
TITLE = "Audit log export for quarterly access reviews"


def test_a_pushed_issue_is_opened_and_commented_on(live_site, browser):
    story = BrowserStory.start(live_site, browser, SCENARIO)
    page = story.page
    tabs = page.get_by_role("navigation", name="Repository").last
    expect(page.get_by_role("region", name="README")).to_be_visible()
    tabs.get_by_role("link", name=re.compile(r"^Issues")).click()
    issues = page.get_by_role("region", name="Issues")
    expect(
        issues.get_by_role("link", name="Add a keyboard shortcut to jump between boards")
    ).to_be_visible()
    expect(issues.get_by_role("link", name=TITLE)).to_have_count(0)
    expect(page.get_by_label("open issues")).to_have_text("3")
    story.watch_for_reload()

    story.advance(FILED_AT)
    expect(issues.get_by_role("link", name=TITLE)).to_be_visible()
    expect(page.get_by_label("open issues")).to_have_text("6")
    story.assert_not_reloaded()
    expect(page.get_by_text("SOC 2 compliance reviews")).to_have_count(0)

    issues.get_by_role("link", name=TITLE).click()
    expect(page.get_by_role("heading", level=1, name=re.compile(TITLE))).to_be_visible()
    expect(page.get_by_text(re.compile("SOC 2 compliance reviews"))).to_be_visible()
    page.get_by_label("Add a comment").last.fill("Thanks, routing this to the security team.")
    page.get_by_role("button", name="Comment", exact=True).click()
    expect(page.get_by_text("Thanks, routing this to the security team.")).to_be_visible()

    assert story.report() == [
        ("view_issue", {"issue_id": "i20"}),
        (
            "comment_issue",
            {
                "issue_id": "i20",
                "body": "Thanks, routing this to the security team.",
                "id": "user-comment-1",
            },
        ),
    ]
