"""What each screen shows, as plain values: pure functions of the account and `now`.

Everything is computed from the account settled to `now` (resting orders filled by then) and
prices at `now`, the same values the evaluation tables hold at that instant. Rows are frozen
dataclasses of display text, so `render_fragment` reuses a row while its text is unchanged.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

from apps.kit.charts import Chart, chart, earlier_today, session_samples, sparkline
from apps.kit.derived import per_state
from apps.microhood import state as account
from apps.microhood.orders import next_fill_time, settle
from apps.microhood.state import Hood, NewsItem, Order

PRICE_STEP = 0.01  # prices are shown to the cent
REFRESH_S = 1.0  # moving prices are re-shown at most once per simulated second
SPARK_SAMPLES = 24


def money(value: float) -> str:
    return f"-${-value:,.2f}" if value < 0 else f"${value:,.2f}"


@dataclass(frozen=True)
class Change:
    """A change in dollars and in percent, shown with one sign and one colour: "-$0.0033
    (-3.95%)" in red, never "+$0.00 (-3.95%)" (a coin under a dollar moves by fractions of a
    cent, so its dollars keep the four decimals its price has)."""

    amount: str
    percent: str
    up: bool

    @classmethod
    def of(cls, delta: float, percent: float, price: float) -> Change:
        tiny = round(delta, 2) == 0 and round(percent, 2) != 0  # a move of under a cent
        places = 4 if 0 < abs(price) < 1 or tiny else 2
        size, pct = f"{abs(delta):,.{places}f}", f"{abs(percent):,.2f}"
        down = delta < 0 and bool((size + pct).strip("0.,"))  # a change shown as zero is "+"
        sign = "-" if down else "+"
        return cls(f"{sign}${size}", f"{sign}{pct}%", not down)


def price_text(value: float) -> str:
    """Prices under a dollar (some coins) keep four decimals, as brokers show them."""
    return f"${value:,.4f}" if 0 < value < 1 else money(value)


@dataclass(frozen=True)
class Row:
    """A stock in a list (holdings, watchlist, market cards, search)."""

    symbol: str
    name: str
    price: str
    change: str
    percent: str
    up: bool
    detail: str  # "12 shares", a sector…
    spark: str  # sparkline path ("" for none)
    logo: str  # seed for {% logo %}


@per_state()
def settled(hood: Hood, now: float) -> Hood:
    return settle(hood, now)


def row(hood: Hood, symbol: str, now: float, detail: str = "", spark: bool = False) -> Row:
    stock = hood.stocks[symbol]
    delta, percent = account.change(hood, symbol, now)
    price = shown_price(hood, symbol, now)
    shown = Change.of(delta, percent, price)
    series = hood.prices[symbol]
    line = ""
    if spark:  # the day so far, as the 1D chart draws it
        today = [v for _, v in session_samples(series.value_at, now, SPARK_SAMPLES)]
        line = sparkline([*earlier_today(symbol, today[0]), *today])
    return Row(
        symbol=symbol,
        name=stock.name,
        price=price_text(price),
        change=shown.amount,
        percent=shown.percent,
        up=shown.up,
        detail=detail,
        spark=line,
        logo=stock.name,
    )


def shown_price(hood: Hood, symbol: str, now: float) -> float:
    """The cent-rounded quote, but four decimals under a dollar (as crypto is shown)."""
    value = account.price(hood, symbol, now)
    return round(value, 4) if 0 < value < 1 else round(value, 2)


def shares_text(shares: int) -> str:
    return f"{shares:,} share{'s' if shares != 1 else ''}"


def held_symbols(hood: Hood) -> list[str]:
    """Positions with shares, in listing order (the original hides the rest)."""
    return [s for s in hood.stocks if hood.holding(s).shares > 0]


@per_state()
def holding_rows(hood: Hood, now: float) -> list[Row]:
    hood = settled(hood, now)
    return [
        row(hood, s, now, shares_text(hood.holding(s).shares), spark=True)
        for s in held_symbols(hood)
    ]


@per_state()
def watch_rows(hood: Hood, now: float) -> list[Row]:
    return [
        row(hood, s, now, spark=True) for s in account.watchlist_symbols(hood) if s in hood.stocks
    ]


@dataclass(frozen=True)
class Portfolio:
    value: str
    change: str
    percent: str
    up: bool
    buying_power: str
    chart: Chart


@per_state()
def portfolio(hood: Hood, now: float, range_name: str, span: float) -> Portfolio:
    """The headline and chart: value now and its change since the task started."""
    hood = settled(hood, now)
    value = account.portfolio_value(hood, now)
    delta = value - hood.opening_value
    percent = delta / hood.opening_value * 100 if hood.opening_value else 0.0
    line = chart("portfolio", range_name, lambda t: account.portfolio_value(hood, t), now, span)
    shown = Change.of(delta, percent, value)
    return Portfolio(
        value=money(value),
        change=shown.amount,
        percent=shown.percent,
        up=shown.up,
        buying_power=money(hood.buying_power),
        chart=line,
    )


@dataclass(frozen=True)
class Position:
    shares: int
    available: int
    market_value: str
    avg_cost: str
    total_return: str
    total_return_up: bool


@dataclass(frozen=True)
class StockScreen:
    row: Row
    stock: account.Stock
    price: float
    chart: Chart
    position: Position | None
    watching: bool
    news: list[NewsItem]
    stats: list[tuple[str, str]]


def position(hood: Hood, symbol: str, now: float) -> Position | None:
    held = hood.holding(symbol)
    if held.shares <= 0:
        return None
    value = held.shares * account.quote(hood, symbol, now)
    gain = value - held.shares * held.avg_cost
    percent = gain / (held.shares * held.avg_cost) * 100 if held.avg_cost else 0.0
    shown = Change.of(gain, percent, value)
    return Position(
        shares=held.shares,
        available=account.shares_available(hood, symbol),
        market_value=money(value),
        avg_cost=money(held.avg_cost),
        total_return=f"{shown.amount} ({shown.percent})",
        total_return_up=shown.up,
    )


def big_number(value: float | None) -> str:
    if value is None:
        return "—"
    for unit, size in (("T", 1e12), ("B", 1e9), ("M", 1e6)):
        if value >= size:
            return f"{value / size:.2f}{unit}"
    return f"{value:,.0f}"


@per_state()
def stock_screen(hood: Hood, symbol: str, now: float, range_name: str, span: float) -> StockScreen:
    hood = settled(hood, now)
    stock = hood.stocks[symbol]
    series = hood.prices[symbol]
    stats = [
        ("Market cap", big_number(stock.market_cap)),
        ("P/E ratio", f"{stock.pe_ratio:.1f}" if stock.pe_ratio else "—"),
        ("Dividend yield", f"{stock.dividend_yield:.2f}%" if stock.dividend_yield else "—"),
        ("Open", price_text(round(series.start, 2))),
        ("Today's high", price_text(max(v for _, v in session_samples(series.value_at, now)))),
        ("Today's low", price_text(min(v for _, v in session_samples(series.value_at, now)))),
    ]
    return StockScreen(
        row=row(hood, symbol, now, stock.sector),
        stock=stock,
        price=account.quote(hood, symbol, now),
        chart=chart(symbol, range_name, series.value_at, now, span),
        position=position(hood, symbol, now),
        watching=symbol in account.watchlist_symbols(hood),
        news=[n for n in newest_first(hood.news.values()) if symbol in n.symbols],
        stats=stats,
    )


def newest_first(news: Iterable[NewsItem]) -> list[NewsItem]:
    """Newest story on top; stories of the same moment keep the later arrival first (the sort
    is stable, so equal times keep the reversed arrival order)."""
    return sorted(reversed(list(news)), key=lambda n: n.published_at, reverse=True)


@per_state()
def market(hood: Hood, now: float) -> tuple[list[Row], list[Row]]:
    """(equities, crypto) cards."""
    equities = [
        row(hood, s, now, st.sector) for s, st in hood.stocks.items() if st.asset_class != "crypto"
    ]
    coins = [
        row(hood, s, now, "Crypto") for s, st in hood.stocks.items() if st.asset_class == "crypto"
    ]
    return equities, coins


def search(hood: Hood, query: str, now: float) -> list[Row]:
    """Symbol or name containing the text, case-insensitive; symbol matches first."""
    needle = query.strip().casefold()
    if not needle:
        return []
    hits = [
        s for s, st in hood.stocks.items() if needle in s.casefold() or needle in st.name.casefold()
    ]
    hits.sort(key=lambda s: (not s.casefold().startswith(needle), s))
    return [row(hood, s, now, hood.stocks[s].sector) for s in hits]


@dataclass(frozen=True)
class OrderRow:
    order: Order
    name: str
    what: str  # "Market buy", "Limit sell"
    limit: str
    price: str
    total: str


def order_rows(hood: Hood, now: float) -> list[OrderRow]:
    hood = settled(hood, now)
    return [
        OrderRow(
            order=o,
            name=hood.stocks[o.symbol].name if o.symbol in hood.stocks else o.symbol,
            what=f"{o.type.title()} {o.side}",
            limit=money(o.limit_price) if o.limit_price is not None else "",
            price=money(o.price) if o.price is not None else "",
            total=money(o.price * o.quantity) if o.price is not None else "",
        )
        for o in reversed(hood.orders)
    ]


def resting_orders(hood: Hood, symbol: str, now: float) -> list[Order]:
    return [o for o in account.pending_orders(settled(hood, now)) if o.symbol == symbol]


def next_shown_change(
    hood: Hood, symbols: Iterable[str], now: float, horizon: float
) -> float | None:
    """When a shown price (to the cent) or a resting order next changes, no sooner than the next
    whole simulated second (the refresh cap); None when nothing shown moves again."""
    due = [hood.prices[s].next_change(now, step=PRICE_STEP) for s in symbols if s in hood.prices]
    due.append(next_fill_time(settled(hood, now), now, horizon))
    due = [t for t in due if t is not None]
    if not due:
        return None
    return max(min(due), math.floor(now + 1e-9) + REFRESH_S)
