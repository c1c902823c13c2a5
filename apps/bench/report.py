"""`bench grade --html PATH`: one self-contained HTML file, plots drawn as inline SVG.

No scripts, fonts or stylesheets from the network: the file opens anywhere, offline. Plots (the
paper's evaluation figures): success by category, cost per task, task completion time vs
target time (with the y = x diagonal), cost vs target time.
"""

from __future__ import annotations

import math
from html import escape
from pathlib import Path

from apps.bench.grading import GROUPS, Row, mean, median, render_table, summarise

W, H = 560, 340
M_LEFT, M_RIGHT, M_TOP, M_BOTTOM = 64, 20, 44, 56  # top: room for the title and bar labels
BLUE, RED, GREY = "#1f6fb4", "#c8322d", "#888"
GROUP_LABELS = {
    "overall": "overall",
    "noop": "no-op",
    "passive": "passive",
    "active": "active",
    "absolute": "absolute",
    "relative": "relative",
}


def nice_ticks(low: float, high: float, count: int = 5) -> list[float]:
    if high <= low:
        high = low + 1
    raw = (high - low) / count
    magnitude = 10 ** math.floor(math.log10(raw))
    step = min((m * magnitude for m in (1, 2, 2.5, 5, 10) if m * magnitude >= raw), default=raw)
    ticks = [math.floor(low / step) * step]
    while ticks[-1] < high - step * 1e-9:  # the last tick is at or above `high`: every mark fits
        ticks.append(round(ticks[-1] + step, 10))
    return ticks


def _fmt(value: float) -> str:
    return f"{value:g}" if abs(value) >= 0.01 or value == 0 else f"{value:.3g}"


class Plot:
    """A tiny SVG chart: linear axes, ticks, labels; the caller adds marks in data coordinates."""

    def __init__(
        self,
        plot_id: str,
        title: str,
        x_label: str,
        y_label: str,
        x_range: tuple[float, float],
        y_range: tuple[float, float],
    ):
        self.id, self.title, self.x_label, self.y_label = plot_id, title, x_label, y_label
        self.x_ticks = nice_ticks(*x_range)
        self.y_ticks = nice_ticks(*y_range)
        self.x0, self.x1 = self.x_ticks[0], self.x_ticks[-1]
        self.y0, self.y1 = self.y_ticks[0], self.y_ticks[-1]
        self.marks: list[str] = []

    def sx(self, x: float) -> float:
        return M_LEFT + (x - self.x0) / ((self.x1 - self.x0) or 1) * (W - M_LEFT - M_RIGHT)

    def sy(self, y: float) -> float:
        return H - M_BOTTOM - (y - self.y0) / ((self.y1 - self.y0) or 1) * (H - M_TOP - M_BOTTOM)

    def add(self, mark: str) -> None:
        self.marks.append(mark)

    def render(self, *, x_categories: list[str] | None = None) -> str:
        parts = [
            f'<svg id="{self.id}" class="plot" xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" '
            f'viewBox="0 0 {W} {H}" role="img" aria-label="{escape(self.title)}">',
            f'<text x="{W / 2}" y="18" text-anchor="middle" class="title">{escape(self.title)}</text>',
        ]
        for y in self.y_ticks:
            parts.append(
                f'<line class="grid" x1="{M_LEFT}" x2="{W - M_RIGHT}" y1="{self.sy(y):.1f}" y2="{self.sy(y):.1f}"/>'
            )
            parts.append(
                f'<text x="{M_LEFT - 6}" y="{self.sy(y) + 4:.1f}" text-anchor="end">{_fmt(y)}</text>'
            )
        if x_categories is None:
            for x in self.x_ticks:
                parts.append(
                    f'<text x="{self.sx(x):.1f}" y="{H - M_BOTTOM + 16}" text-anchor="middle">{_fmt(x)}</text>'
                )
        parts.append(
            f'<line class="axis" x1="{M_LEFT}" x2="{W - M_RIGHT}" y1="{H - M_BOTTOM}" y2="{H - M_BOTTOM}"/>'
        )
        parts.append(
            f'<line class="axis" x1="{M_LEFT}" x2="{M_LEFT}" y1="{M_TOP}" y2="{H - M_BOTTOM}"/>'
        )
        parts.append(
            f'<text x="{(M_LEFT + W - M_RIGHT) / 2}" y="{H - 12}" text-anchor="middle">{escape(self.x_label)}</text>'
        )
        parts.append(
            f'<text transform="translate(16 {(M_TOP + H - M_BOTTOM) / 2}) rotate(-90)" '
            f'text-anchor="middle">{escape(self.y_label)}</text>'
        )
        parts.extend(self.marks)
        parts.append("</svg>")
        return "\n".join(parts)


def _dot(plot: Plot, x: float, y: float, success: bool, title: str) -> str:
    cx, cy = plot.sx(x), plot.sy(y)
    tip = f"<title>{escape(title)}</title>"
    if success:
        return f'<circle class="mark ok" cx="{cx:.1f}" cy="{cy:.1f}" r="5" fill="{BLUE}">{tip}</circle>'
    d = f"M{cx - 5:.1f},{cy - 5:.1f}L{cx + 5:.1f},{cy + 5:.1f}M{cx - 5:.1f},{cy + 5:.1f}L{cx + 5:.1f},{cy - 5:.1f}"
    return f'<path class="mark fail" d="{d}" stroke="{RED}" stroke-width="2.2" fill="none">{tip}</path>'


def _empty(plot: Plot, message: str) -> None:
    plot.add(
        f'<text class="empty" x="{W / 2}" y="{H / 2}" text-anchor="middle">{escape(message)}</text>'
    )


def success_plot(rows: list[Row]) -> str:
    rates = summarise(rows).rates
    plot = Plot(
        "plot-success",
        "Success rate by category",
        "category",
        "success (%)",
        (0, len(GROUPS)),
        (0, 100),
    )
    plot.x0, plot.x1 = 0, len(GROUPS)
    band = (W - M_LEFT - M_RIGHT) / len(GROUPS)
    for i, group in enumerate(GROUPS):
        rate = rates[group]
        x = M_LEFT + i * band + band * 0.15
        label = f"{GROUP_LABELS[group]}"
        plot.add(
            f'<text x="{x + band * 0.35:.1f}" y="{H - M_BOTTOM + 16}" text-anchor="middle">{label}</text>'
        )
        if rate.total:
            value = 100 * rate.fraction
            top = plot.sy(value)
            plot.add(
                f'<rect class="mark bar" x="{x:.1f}" y="{top:.1f}" width="{band * 0.7:.1f}" '
                f'height="{plot.sy(0) - top:.1f}" fill="{BLUE if group != "overall" else "#274b6d"}">'
                f"<title>{label}: {rate}</title></rect>"
            )
            plot.add(
                f'<text x="{x + band * 0.35:.1f}" y="{top - 4:.1f}" text-anchor="middle">'
                f"{value:.0f}% ({rate.passed}/{rate.total})</text>"
            )
    return plot.render(x_categories=list(GROUPS))


def cost_plot(rows: list[Row]) -> str:
    costed = sorted((r for r in rows if r.cost_usd is not None), key=lambda r: r.cost_usd)
    top = max((r.cost_usd for r in costed), default=1.0) or 1.0
    plot = Plot(
        "plot-cost",
        "API cost per task (USD)",
        "task (sorted by cost)",
        "cost (USD)",
        (0, max(1, len(costed))),
        (0, top),
    )
    if not costed:
        _empty(plot, "no costs.json with a priced model")
        return plot.render(x_categories=[])
    band = (W - M_LEFT - M_RIGHT) / len(costed)
    for i, row in enumerate(costed):
        y = plot.sy(row.cost_usd)
        plot.add(
            f'<rect class="mark bar" x="{M_LEFT + i * band + band * 0.1:.1f}" y="{y:.1f}" '
            f'width="{max(1.0, band * 0.8):.1f}" height="{plot.sy(0) - y:.1f}" '
            f'fill="{BLUE if row.success else RED}"><title>{escape(row.name)}: ${row.cost_usd:.4f}</title></rect>'
        )
    costs = [r.cost_usd for r in costed]
    y = plot.sy(median(costs))
    plot.add(
        f'<line class="median" x1="{M_LEFT}" x2="{W - M_RIGHT}" y1="{y:.1f}" y2="{y:.1f}" '
        f'stroke="{GREY}" stroke-dasharray="5 4"><title>median ${median(costs):.4f}, mean ${mean(costs):.4f}</title></line>'
    )
    return plot.render(x_categories=[])


def _targeted(rows: list[Row]) -> list[Row]:
    return [r for r in rows if r.condition_at is not None]


def time_plot(rows: list[Row]) -> str:
    points = [(r, r.completion_time) for r in _targeted(rows) if r.completion_time is not None]
    limit = max([r.condition_at for r, _ in points] + [t for _, t in points] + [1.0])
    plot = Plot(
        "plot-time",
        "Task completion time vs target time",
        "target time (s)",
        "completion time (s)",
        (0, limit),
        (0, limit),
    )
    plot.add(
        f'<line class="diagonal" x1="{plot.sx(0):.1f}" y1="{plot.sy(0):.1f}" x2="{plot.sx(plot.x1):.1f}" '
        f'y2="{plot.sy(min(plot.x1, plot.y1)):.1f}" stroke="{GREY}" stroke-dasharray="4 3"/>'
    )
    if not points:
        _empty(plot, "no task with a target time")
    for row, t in points:
        plot.add(
            _dot(
                plot,
                row.condition_at,
                t,
                row.success,
                f"{row.name}: target {row.condition_at:.1f}s, completed {t:.1f}s",
            )
        )
    return plot.render()


def cost_time_plot(rows: list[Row]) -> str:
    points = [r for r in _targeted(rows) if r.cost_usd is not None]
    x_top = max([r.condition_at for r in points] + [1.0])
    y_top = max([r.cost_usd for r in points] + [0.0]) or 1.0
    plot = Plot(
        "plot-cost-time",
        "API cost vs target time",
        "target time (s)",
        "cost (USD)",
        (0, x_top),
        (0, y_top),
    )
    if not points:
        _empty(plot, "no priced task with a target time")
    for row in points:
        plot.add(
            _dot(
                plot,
                row.condition_at,
                row.cost_usd,
                row.success,
                f"{row.name}: target {row.condition_at:.1f}s, ${row.cost_usd:.4f}",
            )
        )
    return plot.render()


STYLE = """
body{font:14px/1.45 system-ui,sans-serif;margin:24px;color:#222;max-width:1200px}
h1{font-size:20px} .plots{display:flex;flex-wrap:wrap;gap:16px}
svg.plot{border:1px solid #ddd;background:#fff} svg text{font-size:11px;fill:#333}
svg text.title{font-size:13px;font-weight:600} .grid{stroke:#eee} .axis{stroke:#666}
pre{background:#f6f6f6;padding:12px;overflow:auto;font-size:12px}
"""


def render_report(name: str, rows: list[Row]) -> str:
    plots = [success_plot(rows), cost_plot(rows), time_plot(rows), cost_time_plot(rows)]
    return (
        '<!doctype html>\n<html lang="en"><head><meta charset="utf-8">'
        f"<title>Benchmark report: {escape(name)}</title><style>{STYLE}</style></head><body>"
        f"<h1>Benchmark report: {escape(name)}</h1>"
        f'<div class="plots">{"".join(plots)}</div>'
        f"<h2>Tasks</h2><pre>{escape(render_table(rows))}</pre>"
        "</body></html>\n"
    )


def write_report(path: Path, name: str, rows: list[Row]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(render_report(name, rows), encoding="utf-8")
