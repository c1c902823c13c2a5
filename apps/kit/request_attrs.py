"""What the site keeps on a request beyond Django's own attributes, read and set here only.

- `htmx`: django-htmx's details (its middleware sets them; apps.kit.live sets them on a live
  render; a request built otherwise has none);
- `sentinel_page`: the Page that @run_page made for the request (what a live render reads back);
- `sentinel_sim_clock`: the run's simulated time this request was served at and the rate its
  clock moves (set by @run_page, sent as response headers by apps.kit.sim_clock_header);
- `sentinel_live`: a live re-render (apps.kit.live), which logs nothing and performs nothing;
- `sentinel_live_regions`: the regions such a render recorded, in page order, as (id, outer HTML
  with hx-swap-oob) — filled by the `{% live %}` tag, which counts its nesting in
  `sentinel_live_depth` (only the outermost region is sent: it holds the inner ones).

A request may lack any of them, so each is read with a default; `object` parameters because the
template tag reads them off whatever its context holds as the request.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING, Protocol

if TYPE_CHECKING:
    from django_htmx.middleware import HtmxDetails


class RenderedPage(Protocol):
    """What a live render reads back of the page it rendered (an apps.kit.pages.Page, which
    imports this module: named by what is read, not imported)."""

    live_seq: int
    next_change: float | None


Region = tuple[str, str]  # (id, outer HTML with hx-swap-oob)

HTMX = "htmx"
PAGE = "sentinel_page"
SIM_CLOCK = "sentinel_sim_clock"
LIVE = "sentinel_live"
LIVE_REGIONS = "sentinel_live_regions"
LIVE_DEPTH = "sentinel_live_depth"


def htmx(request: object) -> HtmxDetails | None:
    return getattr(request, HTMX, None)


def page(request: object) -> RenderedPage | None:
    return getattr(request, PAGE, None)


def set_page(request: object, page: RenderedPage) -> None:
    setattr(request, PAGE, page)


def sim_clock(request: object) -> tuple[float, float] | None:
    """(simulated seconds, simulated seconds per wall second) of the run a page showed."""
    return getattr(request, SIM_CLOCK, None)


def set_sim_clock(request: object, now: float, rate: float) -> None:
    setattr(request, SIM_CLOCK, (now, rate))


def is_live(request: object) -> bool:
    return bool(getattr(request, LIVE, False))


def make_live(request: object, htmx: HtmxDetails) -> None:
    """Flag `request` as a live render, its htmx details `htmx`, no region recorded yet."""
    setattr(request, HTMX, htmx)
    setattr(request, LIVE, True)
    setattr(request, LIVE_REGIONS, [])


def live_regions(request: object) -> list[Region]:
    """The regions recorded on `request` so far (the list is made on first use)."""
    regions = getattr(request, LIVE_REGIONS, None)
    if regions is None:
        regions = []
        setattr(request, LIVE_REGIONS, regions)
    return regions


@contextmanager
def live_region(request: object) -> Iterator[bool]:
    """Rendering one `{% live %}` region of `request`: yields whether it is the outermost."""
    depth = getattr(request, LIVE_DEPTH, 0)
    setattr(request, LIVE_DEPTH, depth + 1)
    try:
        yield not depth
    finally:
        setattr(request, LIVE_DEPTH, getattr(request, LIVE_DEPTH) - 1)
