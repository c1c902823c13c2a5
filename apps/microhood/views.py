"""MicroHood pages: thin views over `screens`, actions through `page.act`, post/redirect/get.

Each page registers when what it shows next changes with the clock (`watch`): a moving price
at the next cent, capped to once per simulated second, and a resting order's fill.
"""

from __future__ import annotations

from collections.abc import Iterable

from django.http import HttpRequest, HttpResponse

from apps.kit.pages import Page, chosen, form_view, screen_view
from apps.kit.rendering import back_field, redirect_after, render_screen
from apps.kit.streaming import present
from apps.microhood import screens
from apps.microhood import state as account
from apps.microhood.query import RANGES, ChartQuery, SearchQuery, StockQuery
from events.registry import ActionRejected

SESSION_SPAN = 720.0  # the 1D chart's width in simulated seconds (the usual timeline end)


def span(page: Page) -> float:
    return max(SESSION_SPAN, float(page.run.event_timeline_end or 0.0))


def watch(page: Page, symbols: Iterable[str]) -> None:
    page.changes_at(screens.next_shown_change(page.state, symbols, page.now, span(page)))


def show(request: HttpRequest, page: Page, template: str, tab: str, **context) -> HttpResponse:
    """`microhood/<template>.html` under the `tab`, with what every page's chrome shows."""
    hood = screens.settled(page.state, page.now)
    chrome = {
        "root": page.root + "/",
        "tab": tab,
        "self_name": hood.self_name,
        "buying_power": screens.money(hood.buying_power),
        "ranges": RANGES,
    }
    return render_screen(request, page, f"microhood/{template}.html", {**chrome, **context})


def investing(request: HttpRequest, page: Page, template: str, **context) -> HttpResponse:
    """A page of the Investing tab, with its Stocks / Lists sidebar."""
    holdings = screens.holding_rows(page.state, page.now)
    watchlist = screens.watch_rows(page.state, page.now)
    return show(
        request, page, template, "investing", holdings=holdings, watchlist=watchlist, **context
    )


@screen_view
def home(request: HttpRequest, page: Page) -> HttpResponse:
    query = ChartQuery.from_params(request.GET)
    hood = page.state
    watch(page, [*hood.holdings, *account.watchlist_symbols(hood)])
    return investing(
        request,
        page,
        "home",
        query=query,
        portfolio=screens.portfolio(hood, page.now, query.range, span(page)),
        news=screens.newest_first(hood.news.values())[:8],
    )


def listed(page: Page, symbol: str) -> None:
    present(page.state.stocks.get(symbol), "stock")  # unknown, or not loaded: alike


@screen_view
def stock(request: HttpRequest, page: Page, symbol: str) -> HttpResponse:
    query = StockQuery.from_params(request.GET)
    listed(page, symbol)
    watch(page, [symbol, *page.state.holdings, *account.watchlist_symbols(page.state)])
    return investing(
        request,
        page,
        "stock",
        query=query,
        screen=screens.stock_screen(page.state, symbol, page.now, query.range, span(page)),
        resting=screens.resting_orders(page.state, symbol, page.now),
    )


def _quantity(text: str) -> int:
    try:
        return int(text.strip())
    except ValueError:
        raise ActionRejected(f"quantity {text!r} is not a whole number of shares") from None


def _limit(text: str) -> float | None:
    text = text.strip().lstrip("$").replace(",", "")
    if not text:
        return None
    try:
        return float(text)
    except ValueError:
        raise ActionRejected(f"limit_price {text!r} is not a price") from None


@form_view
def place_order(request: HttpRequest, page: Page, symbol: str) -> HttpResponse:
    """The order ticket: side, type (market|limit), quantity, limit_price."""
    listed(page, symbol)
    order_type = request.POST.get("type", "market")
    payload = {
        "symbol": symbol,
        "side": request.POST.get("side", "buy"),
        "quantity": _quantity(request.POST.get("quantity", "")),
        "type": order_type,
    }
    if order_type == "limit":
        payload["limit_price"] = _limit(request.POST.get("limit_price", ""))
    event = page.act("place_order", payload)
    placed = next((o for o in page.state.orders if o.id == event.payload["id"]), None)
    if placed is not None and placed.status == "filled":
        verb = "Bought" if placed.side == "buy" else "Sold"
        shares = screens.shares_text(placed.quantity)
        done = f"{verb} {shares} of {symbol} at {screens.money(placed.price)}"
    else:
        limit = screens.money(payload.get("limit_price") or 0)
        done = f"Limit order placed: {payload['side']} {payload['quantity']} {symbol} at {limit}"
    return redirect_after(request, page, f"stocks/{symbol}?side={payload['side']}", done)


@form_view
def watch_stock(request: HttpRequest, page: Page, symbol: str) -> HttpResponse:
    listed(page, symbol)
    intent = chosen("intent", request.POST.get("intent", "add"), ("add", "remove"))
    action = "add_to_watchlist" if intent == "add" else "remove_from_watchlist"
    page.act(action, {"symbol": symbol})
    done = f"{symbol} {'added to' if intent == 'add' else 'removed from'} your watchlist"
    return redirect_after(request, page, back_field(request, f"stocks/{symbol}"), done)


@screen_view
def market(request: HttpRequest, page: Page) -> HttpResponse:
    hood = page.state
    watch(page, hood.stocks)
    equities, coins = screens.market(hood, page.now)
    return show(request, page, "market", "market", equities=equities, coins=coins)


@screen_view
def watchlist(request: HttpRequest, page: Page) -> HttpResponse:
    watch(page, account.watchlist_symbols(page.state))
    return show(request, page, "watchlist", "lists", rows=screens.watch_rows(page.state, page.now))


@screen_view
def news(request: HttpRequest, page: Page) -> HttpResponse:
    return show(request, page, "news", "news", news=screens.newest_first(page.state.news.values()))


@screen_view
def orders(request: HttpRequest, page: Page) -> HttpResponse:
    watch(page, [])
    return show(request, page, "orders", "orders", orders=screens.order_rows(page.state, page.now))


@form_view
def cancel_order(request: HttpRequest, page: Page) -> HttpResponse:
    page.act("cancel_order", {"order_id": request.POST.get("order_id", "")})
    return redirect_after(request, page, "orders", "Order cancelled")


@screen_view
def search(request: HttpRequest, page: Page) -> HttpResponse:
    query = SearchQuery.from_params(request.GET)
    results = screens.search(page.state, query.q, page.now)
    watch(page, [r.symbol for r in results])
    return show(request, page, "search", "search", query=query, results=results)
