"""A real browser on a real server: the open inbox shows new mail by itself.

Daphne serves the test database (fixtures `live_site`, `browser`); a virtual-clock run is
created and advanced through the multi-run API, exactly as a harness would drive it.
"""

from __future__ import annotations

import pytest

from tests import control_api

pytestmark = pytest.mark.browser

SCENARIO = "micromail-sender-absolute-passive"
OPEN = "base-01"  # preloaded, opened by the "user" before the new mail arrives
ARRIVING = "base-36"  # "Travel policy update", due at t=3.26
ARRIVES_AT = 3.26
# A ceiling for a fully loaded machine, not a latency target: the wait ends as soon as the row
# is there. How fast a push arrives is measured by `manage.py bench_live`, not asserted here.
ARRIVAL_CEILING_MS = 30_000


api = control_api.post


def open_inbox(live_site, browser, *, init_script: str | None = None):
    run = api(live_site, "/api/runs/", {"scenario": SCENARIO, "clock_mode": "virtual"})
    context = browser.new_context(viewport={"width": 1100, "height": 420})
    if init_script:
        context.add_init_script(init_script)
    page = context.new_page()
    page.goto(f"{live_site}/r/{run['token']}/micromail/?folder=inbox&email={OPEN}")
    page.wait_for_load_state("networkidle")
    page.evaluate("window.loadedOnce = true")  # gone if the page reloads
    page.evaluate("window.scrollTo(0, 150)")
    assert page.evaluate("window.scrollY") > 0, "the inbox should be long enough to scroll"
    return run, page


def arriving_row(page):
    return page.locator(f'#message-list a.row-link[href*="email={ARRIVING}"]')


def assert_nothing_else_moved(page, scroll_y: float, url: str) -> None:
    assert page.evaluate("window.loadedOnce") is True, "the page reloaded"
    assert page.evaluate("window.scrollY") == scroll_y
    assert page.url == url
    assert page.locator("#reading-pane h2").inner_text() == "Agenda for our 1:1 on Wednesday"


def test_new_mail_is_pushed_into_the_open_inbox_within_a_second(live_site, browser):
    run, page = open_inbox(live_site, browser)
    page.wait_for_function("() => window.WebSocket && document.getElementById('sentinel-live')")
    # No wait for the subscription: the socket subscribes with the log position the page was
    # rendered at, so an event fired before it subscribes is still pushed to it.
    scroll_y, url = page.evaluate("window.scrollY"), page.url
    assert arriving_row(page).count() == 0

    fired = api(live_site, f"/api/runs/{run['id']}/advance/", {"time": ARRIVES_AT})
    assert [e["payload"]["email_id"] for e in fired["processed_events"]] == [ARRIVING]
    arriving_row(page).wait_for(state="attached", timeout=ARRIVAL_CEILING_MS)
    assert_nothing_else_moved(page, scroll_y, url)

    # A form that arrived in the push posts like any other (its CSRF token was filled in).
    page.get_by_role("button", name="Flag “Travel policy update”").click()
    page.get_by_role("button", name="Unflag “Travel policy update”").wait_for(
        timeout=ARRIVAL_CEILING_MS
    )


def test_without_websockets_the_inbox_polls(live_site, browser):
    run, page = open_inbox(live_site, browser, init_script="window.WebSocket = undefined;")
    scroll_y, url = page.evaluate("window.scrollY"), page.url

    api(live_site, f"/api/runs/{run['id']}/advance/", {"time": ARRIVES_AT})
    # Without a socket only the poll (every 2 s: data-poll-ms) can bring the row.
    arriving_row(page).wait_for(state="attached", timeout=ARRIVAL_CEILING_MS)
    assert_nothing_else_moved(page, scroll_y, url)
