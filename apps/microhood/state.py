"""The brokerage account as immutable values, and the questions pages, baselines and grading ask.
Prices are `Waypoints` series, read as `price(hood, symbol, now)` with the one `now` of the
operation — page, live push and evaluation alike (README: "Prices")."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any, ClassVar

from apps.kit.records import from_catalog, text_or, texts
from apps.kit.state import EMPTY, SelfUserState
from apps.kit.waypoints import Waypoints

ENVIRONMENT = "microhood"
DEFAULT_BUYING_POWER = 10_000.0
SIDES = ("buy", "sell")
ORDER_TYPES = ("market", "limit")


@dataclass(frozen=True)
class Stock:
    """A listing from the catalog (equity or crypto); what never moves."""

    symbol: str
    name: str
    color: str = from_catalog(text_or("color", "#333"), default="#333")
    # "stock" | "crypto"
    asset_class: str = from_catalog(text_or("assetClass", "stock"), default="stock")
    sector: str = from_catalog(text_or("sector"), default="")
    description: str = from_catalog(text_or("description"), default="")
    catalog_avg_cost: float = 0.0  # the `stocks.avgCost` column: the catalog's, not the live one
    market_cap: float | None = None
    pe_ratio: float | None = None
    dividend_yield: float | None = None

    @property
    def id(self) -> str:  # what a delivery files it under
        return self.symbol


@dataclass(frozen=True)
class Holding:
    shares: int = 0
    avg_cost: float = 0.0


@dataclass(frozen=True)
class NewsItem:
    id: str
    source: str = from_catalog(text_or("source"))
    title: str = from_catalog(text_or("title"))
    summary: str = from_catalog(text_or("summary"), default="")
    symbols: tuple[str, ...] = from_catalog(texts("symbols"), default=())
    published_at: float = 0.0  # simulated seconds (negative: before the task started)
    data: str = "{}"  # the catalog row as JSON: the `news.data` column


@dataclass(frozen=True)
class Order:
    """An order as placed. A market order fills when placed; a limit order rests until the
    price reaches its limit (`orders.settle`), or is cancelled."""

    id: str
    symbol: str
    side: str  # "buy" | "sell"
    quantity: int
    type: str  # "market" | "limit"
    placed_at: float
    limit_price: float | None = None
    status: str = "filled"  # "filled" | "pending" | "cancelled"
    price: float | None = None  # the fill price, rounded to the cent
    filled_at: float | None = None

    @property
    def reserved(self) -> float:
        """Buying power a resting buy holds back (its limit × quantity)."""
        if self.status == "pending" and self.side == "buy" and self.limit_price is not None:
            return self.limit_price * self.quantity
        return 0.0


@dataclass(frozen=True)
class WatchRow:
    """A stored watchlist row (the catalog's, or one built from the listing when the user adds
    a symbol). Never removed: taking a symbol off the list clears `on`, as the original did."""

    symbol: str
    data: Mapping[str, Any]  # the row as the `watchlist.data` column holds it
    on: bool = True

    @property
    def id(self) -> str:  # what a delivery files it under
        return self.symbol


@dataclass(frozen=True)
class Hood(SelfUserState):
    FALLBACK: ClassVar[Mapping[str, str]] = MappingProxyType({"name": "Me"})

    stocks: Mapping[str, Stock] = field(default_factory=lambda: EMPTY)  # in preload order
    # symbol → price series (start = starting price)
    prices: Mapping[str, Waypoints] = field(default_factory=lambda: EMPTY)
    # every symbol ever held or traded
    holdings: Mapping[str, Holding] = field(default_factory=lambda: EMPTY)
    watchlist: Mapping[str, WatchRow] = field(default_factory=lambda: EMPTY)
    news: Mapping[str, NewsItem] = field(default_factory=lambda: EMPTY)  # in arrival order
    buying_power: float = DEFAULT_BUYING_POWER
    orders: tuple[Order, ...] = ()  # placement order
    settled_to: float = 0.0  # resting orders are decided up to this simulated second
    opening_value: float = 0.0  # the portfolio value when the preload applied ("Today" vs it)

    def holding(self, symbol: str) -> Holding:
        return self.holdings.get(symbol) or Holding()


# --- prices -----------------------------------------------------------------------------------


def price(hood: Hood, symbol: str, now: float) -> float:
    """The price of `symbol` at `now`, unrounded (the `current_prices` column); 0 for a symbol
    that was never loaded, as the original."""
    series = hood.prices.get(symbol)
    return series.value_at(now) if series is not None else 0.0


def quote(hood: Hood, symbol: str, now: float) -> float:
    """The price as shown and traded: rounded to the cent."""
    return round(price(hood, symbol, now), 2)


def change(hood: Hood, symbol: str, now: float) -> tuple[float, float]:
    """(change, percent) of the shown price since the start of the task."""
    series = hood.prices.get(symbol)
    start = series.start if series is not None else 0.0
    delta = quote(hood, symbol, now) - start
    return delta, (delta / start * 100 if start else 0.0)


# --- the account --------------------------------------------------------------------------------


def positions_value(hood: Hood, now: float) -> float:
    return sum(h.shares * price(hood, s, now) for s, h in hood.holdings.items() if h.shares)


def portfolio_value(hood: Hood, now: float) -> float:
    """Buying power plus the positions at the price of `now` (the original's definition; what a
    resting buy holds back still counts, as Robinhood's total does)."""
    return total_cash(hood) + positions_value(hood, now)


def total_cash(hood: Hood) -> float:
    return hood.buying_power + sum(o.reserved for o in hood.orders)


def shares_available(hood: Hood, symbol: str) -> int:
    """Shares not promised to a resting sell."""
    promised = sum(
        o.quantity
        for o in hood.orders
        if o.status == "pending" and o.side == "sell" and o.symbol == symbol
    )
    return hood.holding(symbol).shares - promised


def watchlist_symbols(hood: Hood) -> list[str]:
    return [s for s, row in hood.watchlist.items() if row.on]


def mcro_price(hood: Hood, now: float) -> float:
    """The original's `baseline_mcro_price` (its flagship listing; 0 when not loaded)."""
    return price(hood, "MCRO", now)


def pending_orders(hood: Hood) -> list[Order]:
    return [o for o in hood.orders if o.status == "pending"]


def filled_orders(hood: Hood) -> list[Order]:
    return [o for o in hood.orders if o.status == "filled"]
