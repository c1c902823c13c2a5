"""The MicroHood pages worth timing (`manage.py bench_pages --env microhood`), from the state."""

from __future__ import annotations

from apps.microhood.query import RANGES
from apps.microhood.state import Hood


def sample_pages(hood: Hood) -> list[str]:
    pages = ["", "?range=1W", "market", "news", "orders", "watchlist", "search?q=an"]
    held = [s for s in hood.stocks if hood.holding(s).shares > 0]
    for symbol in held[:1] or list(hood.stocks)[:1]:
        pages += [f"stocks/{symbol}", f"stocks/{symbol}?range={RANGES[-1]}&side=sell"]
    return pages
