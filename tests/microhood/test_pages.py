"""MicroHood's pages: every screen renders with its live regions, unloaded symbols are 404s,
orders and the watchlist go through the forms, and — the point of the environment — the page,
its live push and the evaluation tables show the same prices at the same simulated instant."""

from __future__ import annotations

import re
import sqlite3

import pytest

from apps.kit.live import render_update
from apps.microhood import state as account
from events import lifecycle
from events.commands import current_state
from events.evaluation import grading_snapshot
from tests.microhood.conftest import url

pytestmark = pytest.mark.django_db

SCREENS = [
    "",
    "?range=1W",
    "market",
    "watchlist",
    "news",
    "orders",
    "search?q=bro",
    "stocks/BRKW",
    "stocks/MRDN?range=ALL&side=sell",
]


def html(response) -> str:
    assert response.status_code == 200, response.content[:300]
    return response.content.decode()


def region(text: str, region_id: str) -> str:
    match = re.search(rf'<(\w+) id="{region_id}"[^>]*>(.*?)</\1>', text, re.S)
    assert match, f"no region {region_id}"
    return match.group(2)


def first_price(text: str) -> str:
    return re.search(r"\$[\d,]+\.\d{2}", text).group(0)


@pytest.mark.parametrize("screen", SCREENS)
def test_every_screen_renders_in_the_shell_with_live_regions(browser, hood_run, screen):
    run = hood_run("price-absolute-passive")
    text = html(browser.get(url(run, screen)))
    assert 'id="main"' in text and "data-live" in text and "MicroHood" in text


def test_a_symbol_not_loaded_and_a_bad_range_are_refused(browser, hood_run):
    run = hood_run("price-absolute-passive")
    assert browser.get(url(run, "stocks/NOPE")).status_code == 404
    bad = browser.get(url(run, "?range=5Y"))
    assert bad.status_code == 400 and b"range" in bad.content


@pytest.mark.parametrize("now", [0.0, 217.3, 433.61, 433.62, 433.63, 600.0])
def test_page_live_push_and_evaluation_show_the_same_price_at_the_same_instant(
    browser, hood_run, now
):
    run = hood_run("price-absolute-passive")
    lifecycle.advance(run, now)
    run.refresh_from_db()
    page = region(html(browser.get(url(run, "stocks/BRKW"))), "stock-price")
    pushed = dict(render_update(run, url(run, "stocks/BRKW")).regions)["stock-price"]
    conn = sqlite3.connect(":memory:")
    grading_snapshot(run).write(conn)
    graded = conn.execute("SELECT price FROM current_prices WHERE symbol='BRKW'").fetchone()[0]
    shown = f"${round(graded, 2):,.2f}"
    assert first_price(page) == first_price(pushed) == shown
    assert (graded >= 520.0) is (now >= 433.62)


def test_the_portfolio_headline_is_the_evaluated_total(browser, hood_run):
    run = hood_run("portfolio-absolute-passive")
    lifecycle.advance(run, 385.84)
    run.refresh_from_db()
    headline = first_price(region(html(browser.get(url(run))), "portfolio"))
    conn = sqlite3.connect(":memory:")
    grading_snapshot(run).write(conn)
    total = conn.execute(
        "SELECT CAST((SELECT value FROM session_meta WHERE key='buying_power') AS REAL)"
        " + SUM(ss.shares * cp.price) FROM stock_states ss JOIN current_prices cp USING (symbol)"
    ).fetchone()[0]
    assert headline == f"${total:,.2f}"


def test_a_page_registers_its_next_price_change_no_sooner_than_the_next_second(browser, hood_run):
    run = hood_run("price-absolute-passive")
    lifecycle.advance(run, 100.25)
    run.refresh_from_db()
    update = render_update(run, url(run, "stocks/BRKW"))
    assert update.next_change == 101.0


def test_a_market_order_through_the_ticket_fills_and_shows_in_history(browser, hood_run):
    run = hood_run("orders-absolute-active")
    lifecycle.advance(run, 150.0)
    ticket = html(browser.get(url(run, "stocks/CRGO")))
    assert 'data-action="place_order"' in ticket
    response = browser.post(
        url(run, "stocks/CRGO/order"), {"side": "buy", "type": "market", "quantity": "2"}
    )
    assert response.status_code == 302
    hood = current_state(run)
    assert hood.orders[-1].price == account.quote(hood, "CRGO", 150.0)
    history = html(browser.get(url(run, "orders")))
    assert "Cargowing Drones" in history and "Filled" in history


def test_a_refused_order_names_the_reason(browser, hood_run):
    run = hood_run("orders-absolute-active")
    response = browser.post(
        url(run, "stocks/CRGO/order"), {"side": "sell", "type": "market", "quantity": "99"}
    )
    assert response.status_code == 400 and b"Not enough shares" in response.content


def test_the_star_adds_and_removes_a_watchlist_item(browser, hood_run):
    run = hood_run("price-absolute-passive")
    browser.post(url(run, "stocks/BRKW/watch"), {"intent": "add"})
    assert "BRKW" in account.watchlist_symbols(current_state(run))
    assert "Remove from Lists" in html(browser.get(url(run, "stocks/BRKW")))
    browser.post(url(run, "stocks/BRKW/watch"), {"intent": "remove", "back": "watchlist"})
    assert "BRKW" not in account.watchlist_symbols(current_state(run))


def test_a_story_not_arrived_yet_is_absent_then_listed(browser, hood_run):
    run = hood_run("news-count-relative-passive")
    assert "Beryl Lithium delays" not in html(browser.get(url(run, "news")))  # n19 never fires
    lifecycle.advance(run, 388.05)
    news = html(browser.get(url(run, "news")))
    assert news.count('class="news-item"') == 9


def test_a_resting_limit_order_is_cancelled_from_history(browser, hood_run):
    run = hood_run("orders-absolute-active")
    browser.post(
        url(run, "stocks/CRGO/order"),
        {"side": "buy", "type": "limit", "quantity": "3", "limit_price": "30"},
    )
    history = html(browser.get(url(run, "orders")))
    assert "Pending" in history and 'data-action="cancel_order"' in history
    order_id = current_state(run).orders[-1].id
    browser.post(url(run, "orders/cancel"), {"order_id": order_id})
    assert current_state(run).orders[-1].status == "cancelled"


def test_a_story_arriving_during_the_task_is_dated_then_and_listed_first(browser, hood_run):
    run = hood_run("news-count-relative-passive")
    lifecycle.advance(run, 230.0)
    titles = re.findall(r'<h3 id="news-(n\d+)"', html(browser.get(url(run, "news"))))
    assert titles[:2] == ["n08", "n07"]  # arrived at 221.7 and 96.4, above the preloaded six
