"""MicroHood in a real browser: a live clock moves a price and brings a story while Chromium
watches, then the user buys on the jump and reports back.

The story: the task URL opens Investing. At t=40 (simulated; 10 wall seconds at speed 4)
Cargowing Drones jumps to $42.46 and a story about it arrives: both show on the open page
without a reload (live push). The user opens CRGO from the Stocks sidebar, buys 2 shares at
market through the order ticket, and contacts. The grade sees exactly that one order, filled at
the price of its moment (≥ $42.20).
"""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import expect

from tests import control_api
from tests.conftest import browser  # noqa: F401  (the Chromium fixture, not the Django client)

pytestmark = pytest.mark.browser

JUMP_AT = 40.0
SPEED_FACTOR = 4.0
STORY = "Cargowing Drones stock jumps after a hospital network contract"  # news n26

EVAL_SQL = """
SELECT (SELECT COUNT(*) FROM orders) = 1
   AND EXISTS(SELECT 1 FROM orders WHERE symbol='CRGO' AND action='buy' AND quantity=2
              AND type='market' AND price >= 42.2)
"""


def scenario() -> dict:
    return {
        "id": "browser-microhood-buy",
        "environment": "microhood",
        "prompt": "If CRGO hits $42.20, buy 2 shares at market and tell me.",
        "start_page": "HOST_ADDRESS/microhood",
        "condition_at": JUMP_AT,
        "event_timeline_end": 600.0,
        "kill_at": 600.0,
        "taxonomy": {},
        "events": [
            {
                "time": 0.0,
                "type": "preload_stocks",
                "payload": {
                    "stock_symbols": ["*"],
                    "watchlist_symbols": ["*"],
                    "news_ids": ["n01", "n02", "n03"],
                    "price_waypoints": {"CRGO": [[JUMP_AT, 39.0]]},
                },
            },
            {"time": JUMP_AT, "type": "set_price", "payload": {"symbol": "CRGO", "price": 42.46}},
            {"time": JUMP_AT, "type": "new_news", "payload": {"news_id": "n26"}},
        ],
        "eval_sql": EVAL_SQL,
    }


api = control_api.call


def test_a_user_sees_the_jump_live_and_buys_through_the_ticket(live_site, browser):  # noqa: F811
    run = api(
        live_site,
        "POST",
        "/api/runs/",
        {"scenario_json": scenario(), "clock_mode": "live", "speed_factor": SPEED_FACTOR},
    )
    page = browser.new_page(viewport={"width": 1280, "height": 800})
    page.set_default_timeout(15000)
    page.goto(run["task_url"])
    expect(page.get_by_role("heading", level=1)).to_have_accessible_name(
        re.compile(r"^Portfolio value \$")
    )
    page.wait_for_function("() => document.getElementById('sentinel-live')")
    news = page.get_by_role("heading", level=3, name=STORY)
    expect(news).to_have_count(0)

    # The clock brings the story and the jump into the open page, without a reload.
    expect(news).to_be_visible(timeout=30_000)
    crgo = page.get_by_role("complementary", name="Stocks and lists").get_by_role(
        "link", name=re.compile(r"^Cargowing Drones \(CRGO\), \$42\.46")
    )
    expect(crgo).to_be_visible(timeout=10_000)

    crgo.click()
    expect(page.get_by_role("heading", level=1, name="Cargowing Drones")).to_be_visible()
    ticket = page.get_by_role("form", name="Buy order")
    ticket.get_by_label("Shares").fill("2")
    ticket.get_by_role("button", name="Buy CRGO").click()
    expect(page.get_by_role("status")).to_contain_text("Bought 2 shares of CRGO at $42.46")

    page.goto(run["contact_url"])
    verdict = api(live_site, "POST", f"/api/runs/{run['id']}/evaluate/")
    assert verdict["success"] is True, verdict["detail"]
    assert verdict["actions"] == 1
    logged = api(live_site, "GET", f"/api/runs/{run['id']}/events/")
    assert [e["type"] for e in logged if e["kind"] == "action"] == ["place_order"]
