"""MicroScholar in a real browser: a live clock indexes the awaited paper while Chromium watches.

The story: the self user opens the task URL (which starts the clock) on the home page with its
recommended articles. "Deliberate Delegation" is indexed a few simulated seconds later and shows
up in the list without a reload (a live push). The user opens its Cite dialog (which cites it),
reads the MLA line, closes it, saves the paper, and reports back. The grade must see exactly
those two actions.
"""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import Page, expect

from tests import control_api
from tests.conftest import browser  # noqa: F401  (the Chromium fixture)

pytestmark = pytest.mark.browser

ARRIVES_AT = 6.0  # simulated seconds; 1.5 wall seconds at speed factor 4
SPEED_FACTOR = 4.0
TARGET = "paper-041"
TITLE = "Deliberate Delegation: Language Agents for Multi-Step Office Workflows"

EVAL_SQL = f"""
SELECT (SELECT isCited FROM paper_states WHERE paper_id = '{TARGET}') = 1
  AND (SELECT isSaved FROM paper_states WHERE paper_id = '{TARGET}') = 1
  AND (SELECT COUNT(*) FROM paper_states WHERE isCited = 1 OR isSaved = 1) = 1
"""


def scenario() -> dict:
    return {
        "id": "browser-microscholar-cite",
        "environment": "microscholar",
        "prompt": "Cite and save the delegation paper when it is indexed.",
        "start_page": "HOST_ADDRESS/microscholar",
        "condition_at": ARRIVES_AT,
        "event_timeline_end": 600.0,
        "kill_at": 600.0,
        "taxonomy": {},
        "events": [
            {
                "time": 0.0,
                "type": "preload_papers",
                "payload": {"paper_ids": ["paper-021", "paper-022", "paper-023"], "alert_ids": []},
            },
            {"time": ARRIVES_AT, "type": "new_paper", "payload": {"paper_id": TARGET}},
        ],
        "eval_sql": EVAL_SQL,
    }


api = control_api.call


def recommended(page: Page):
    return page.get_by_role("list", name="Recommended articles")


def test_a_user_sees_the_paper_arrive_live_then_cites_and_saves_it(live_site, browser):  # noqa: F811
    run = api(
        live_site,
        "POST",
        "/api/runs/",
        {"scenario_json": scenario(), "clock_mode": "live", "speed_factor": SPEED_FACTOR},
    )
    page = browser.new_page(viewport={"width": 1280, "height": 800})
    page.set_default_timeout(5000)

    page.goto(run["task_url"])
    expect(page.get_by_role("heading", name=re.compile("Recommended articles"))).to_be_visible()
    expect(
        recommended(page).get_by_role(
            "link", name="Faithfulness Checks for Abstractive Meeting Summaries", exact=True
        )
    ).to_be_visible()
    expect(recommended(page).get_by_role("link", name=TITLE, exact=True)).to_have_count(0)

    # Indexed by the clock and pushed into the open page: no reload.
    expect(recommended(page).get_by_role("link", name=TITLE, exact=True)).to_be_visible(
        timeout=15000
    )
    expect(page.get_by_role("heading", name=re.compile("4 articles"))).to_be_visible()

    # The Cite dialog: opening it cites the paper; it shows the five styles.
    page.get_by_role("link", name=f"Cite {TITLE}").click()
    dialog = page.get_by_role("dialog", name="Cite")
    expect(dialog).to_be_visible()
    styles = dialog.get_by_role("table", name="Citation styles")
    for style in ("MLA", "APA", "Chicago", "Harvard", "BibTeX"):
        expect(styles.get_by_role("rowheader", name=style)).to_be_visible()
    expect(styles).to_contain_text('Park, Yuna, et al. "Deliberate Delegation')
    dialog.get_by_role("link", name="Close").click()

    # Save it from the paper page; the library counts it.
    page.get_by_role("button", name="Save to My library").click()
    expect(page.get_by_role("button", name=re.compile("Saved"))).to_be_visible()
    expect(
        page.get_by_role("navigation", name="My Scholar").get_by_role(
            "link", name=re.compile("My library 1")
        )
    ).to_be_visible()

    page.goto(run["contact_url"])
    verdict = api(live_site, "POST", f"/api/runs/{run['id']}/evaluate/")
    assert verdict["success"] is True, verdict["detail"]
    assert verdict["actions"] == 2
    logged = api(live_site, "GET", f"/api/runs/{run['id']}/events/")
    assert [e["type"] for e in logged if e["kind"] == "action"] == ["cite", "save"]
