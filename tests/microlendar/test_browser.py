"""MicroLendar in a real browser: an invitation appears on the live page, Chromium opens it and
drags another event to the next day.

The story: Chris opens the task URL on the week of Thursday 18 September 2025. "Coffee with
Hana" is added when the clock reaches it and appears in the grid without a reload (live push).
Chris opens it (the scenario's solution: its details viewed), closes it, drags "Lunch with Rosa"
onto Friday, and reports back on the contact page. The grade must see exactly those two actions,
the drop logged like the reschedule form's post.
"""

from __future__ import annotations

import copy
import re

import pytest
from playwright.sync_api import Page, expect

from tests.browser_story import BrowserStory

# tests/microlendar/conftest.py binds `browser` to a django.test.Client; this module needs the
# Chromium one from tests/conftest.py.
from tests.conftest import browser  # noqa: F401
from tests.microlendar.cast import CAST, TODAY

pytestmark = pytest.mark.browser

ARRIVES_AT = 6.0  # simulated seconds
EVAL_SQL = """
SELECT (SELECT isViewed FROM event_states WHERE event_id = 'td-05') = 1
  AND (SELECT date(start_time) FROM events WHERE id = 'td-03') = '2025-09-19'
  AND (SELECT SUM(isViewed) FROM event_states) = 1
"""


def scenario() -> dict:
    spec = copy.deepcopy(dict(CAST.scenario))
    spec["id"] = "browser-microlendar-invite"
    spec["start_page"] = "HOST_ADDRESS/microlendar#week"  # upstream's hash form of the view
    spec["condition_at"] = ARRIVES_AT
    spec["events"][1]["time"] = ARRIVES_AT
    spec["eval_sql"] = EVAL_SQL
    return spec


def block(page: Page, title: str):
    return page.get_by_role("list", name="Thursday, September 18").get_by_role(
        "link", name=re.compile("^" + re.escape(title))
    )


def test_a_user_sees_an_event_arrive_opens_it_and_drags_another(live_site, browser):  # noqa: F811
    story = BrowserStory.start(live_site, browser, scenario())
    page = story.page

    # The task URL lands on the week view (the hash became ?view=week), today highlighted.
    expect(page).to_have_url(re.compile(r"\?view=week$"))
    expect(page.get_by_role("heading", level=1, name="September 2025")).to_be_visible()
    expect(block(page, "Daily standup")).to_be_visible()
    expect(page.get_by_role("img", name=re.compile(r"^Current time"))).to_be_visible()
    expect(block(page, "Coffee with Hana")).to_have_count(0)

    # The clock adds the event; the page shows it without being reloaded.
    story.watch_for_reload()
    story.advance(ARRIVES_AT)
    expect(block(page, "Coffee with Hana")).to_be_visible()
    story.assert_not_reloaded()

    # Open its details (the viewed invitation), then close them.
    block(page, "Coffee with Hana").click()
    details = page.get_by_role("dialog", name="Coffee with Hana")
    expect(details).to_contain_text("Thursday, September 18 · 11 – 11:30am")
    expect(details).to_contain_text("Hana Sato")
    details.get_by_role("link", name="Close").click()
    expect(page.get_by_role("dialog")).to_have_count(0)

    # Drag lunch onto Friday: the drop posts the reschedule form's request.
    friday = page.get_by_role("list", name="Friday, September 19")
    block(page, "Lunch with Rosa").drag_to(friday)
    expect(friday.get_by_role("link", name=re.compile(r"^Lunch with Rosa"))).to_be_visible()
    expect(block(page, "Lunch with Rosa")).to_have_count(0)

    actions = story.report()
    assert [name for name, _ in actions] == ["view_event", "reschedule_event"]
    assert set(actions[1][1]) == {"event_id", "date", "time", "endTime"}
    assert actions[1][1]["date"] == "2025-09-19" and TODAY == "2025-09-18"


@pytest.mark.parametrize("view", ["week", "day"])
def test_the_time_grid_opens_with_its_top_hour_label_whole(live_site, browser, view):  # noqa: F811
    """Finding: the grid opened scrolled exactly to an hour line, cutting that hour's label."""
    story = BrowserStory.start(live_site, browser, scenario(), open_task=False)
    page = story.page
    page.goto(story.run["task_url"])
    page.goto(page.url.split("?")[0] + f"?view={view}")
    grid = page.locator("#tg-scroll")
    page.wait_for_function("() => document.getElementById('tg-scroll').dataset.scrolled")
    top = grid.bounding_box()["y"]
    labels = [box for box in (s.bounding_box() for s in grid.locator(".hour span").all()) if box]
    first = min((box for box in labels if box["y"] + box["height"] > top), key=lambda b: b["y"])
    assert first["y"] >= top, "the top hour's label is cut by the grid's edge"
