"""`bench grade --html PATH`: one self-contained HTML file, plots drawn as inline SVG.

No scripts, fonts or stylesheets from the network: the file opens anywhere, offline. Plots (the
paper's evaluation figures): success by category, cost per task, task completion time vs
target time (with the y = x diagonal), cost vs target time. Several result sets give the
paper's comparison instead: success (and timely success) by category side by side, a per-task
cost box plot on a log axis, tool-call and reaction-time tables.

Both open with each set's manifest (what produced it) and give every figure its 95 %
interval, pass@k / pass^k when a set has several trials, the breakdown by environment, and the
errors with their causes (report_sections.py); several sets also say whether their differences
are larger than the noise.

Both end with a per-task table whose rows link to the task's transcript, rendered as its own
page in `<report stem>-transcripts/` beside the report (apps/bench/transcripts.py).
"""

from __future__ import annotations

import math
from html import escape
from pathlib import Path

from apps.bench.grading import (
    GROUPS,
    ResultSet,
    Row,
    axis_table,
    clocks,
    cost_table,
    mean,
    median,
    quartiles,
    render_table,
    success_table,
    summarise,
    timely_table,
    tool_calls_table,
    unpriced_models,
)
from apps.bench.report_sections import (
    SECTION_STYLE,
    differences_section,
    errors_section,
    manifest_section,
    reports_section,
    uncertainty_section,
)
from apps.bench.timeline_links import timeline_url
from apps.bench.transcripts import has_transcript, relative_href, render_transcript_page
from events.timing import REACTION_WINDOW

TranscriptLinks = dict[tuple[str, str, str], str]  # (result set, environment, task) -> href


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
table{border-collapse:collapse;margin:8px 0 16px} th,td{padding:3px 10px;text-align:left}
thead th{border-bottom:1px solid #999} tbody tr{border-bottom:1px solid #eee}
tr.fail td:nth-child(5){color:#c8322d}
.swatch{display:inline-block;width:10px;height:10px;margin:0 6px 0 2px;border-radius:2px}
.note{color:#555} svg text.note{font-size:10px;fill:#777}
"""


def render_report(
    name: str,
    rows: list[Row],
    window: float = REACTION_WINDOW,
    links: TranscriptLinks | None = None,
    result_set: ResultSet | None = None,
    site: str | None = None,
) -> str:
    rs = result_set or ResultSet(name, rows, [])
    plots = [success_plot(rows), cost_plot(rows), time_plot(rows), cost_time_plot(rows)]
    return (
        '<!doctype html>\n<html lang="en"><head><meta charset="utf-8">'
        f"<title>Benchmark report: {escape(name)}</title>"
        f"<style>{STYLE}{SECTION_STYLE}</style></head><body>"
        f"<h1>Benchmark report: {escape(name)}</h1>"
        f"{manifest_section(rs)}{uncertainty_section(rs, window)}"
        f'<div class="plots">{"".join(plots)}</div>{errors_section(rs)}{reports_section(rs)}'
        f"<h2>Tasks</h2><pre>{escape(render_table(rows, rs.errors, window))}</pre>"
        f"<h2>Per task</h2>{_timely_note(window)}"
        f"{tasks_table([rs], window, links or {}, site)}"
        "</body></html>\n"
    )


def write_report(
    path: Path,
    name: str,
    rows: list[Row],
    window: float = REACTION_WINDOW,
    result_set: ResultSet | None = None,
    site: str | None = None,
) -> None:
    rs = result_set or ResultSet(name, rows, [])
    links = write_transcripts(path, [rs], window)
    path.write_text(render_report(name, rows, window, links, rs, site), encoding="utf-8")


def write_comparison_report(
    path: Path, sets: list[ResultSet], window: float, site: str | None = None
) -> None:
    links = write_transcripts(path, sets, window)
    path.write_text(render_comparison_report(sets, window, links, site), encoding="utf-8")


# --- several result sets ---------------------------------------------------------------------

SET_COLORS = ("#1f6fb4", "#e07b00", "#2a9d4b", "#8e44ad", "#c8322d", "#17a2b8", "#7f6a00", "#555")
COMPARED_GROUPS = ("overall", "timely", *GROUPS[1:])
BOX_W, BOX_ROW, BOX_LEFT = 720, 56, 180  # the cost box plot: one row per result set


def set_color(index: int) -> str:
    return SET_COLORS[index % len(SET_COLORS)]


def _swatch(index: int) -> str:
    return f'<span class="swatch" style="background:{set_color(index)}"></span>'


def comparison_success_plot(sets: list[ResultSet], window: float) -> str:
    """Grouped bars: for each category (and timely success), one bar per result set."""
    summaries = [summarise(rs.rows, window) for rs in sets]
    plot = Plot(
        "plot-compare-success",
        "Success rate by category",
        "category",
        "success (%)",
        (0, len(COMPARED_GROUPS)),
        (0, 100),
    )
    plot.x0, plot.x1 = 0, len(COMPARED_GROUPS)
    band = (W - M_LEFT - M_RIGHT) / len(COMPARED_GROUPS)
    bar = band * 0.8 / len(sets)
    for g, group in enumerate(COMPARED_GROUPS):
        left = M_LEFT + g * band + band * 0.1
        plot.add(
            f'<text x="{left + band * 0.4:.1f}" y="{H - M_BOTTOM + 16}" text-anchor="middle">'
            f"{GROUP_LABELS.get(group, group)}</text>"
        )
        for i, (rs, summary) in enumerate(zip(sets, summaries, strict=True)):
            rate = summary.timely["overall"] if group == "timely" else summary.rates[group]
            if not rate.total:
                continue
            top = plot.sy(100 * rate.fraction)
            plot.add(
                f'<rect class="mark bar" data-set="{escape(rs.name)}" x="{left + i * bar:.1f}" '
                f'y="{top:.1f}" width="{bar * 0.92:.1f}" height="{plot.sy(0) - top:.1f}" '
                f'fill="{set_color(i)}"><title>{escape(rs.name)}, '
                f"{GROUP_LABELS.get(group, group)}: {rate}</title></rect>"
            )
    return plot.render(x_categories=list(COMPARED_GROUPS))


def _decades(values: list[float]) -> tuple[int, int]:
    """Powers of ten enclosing every positive value (a log axis shows no zero)."""
    positive = [v for v in values if v > 0]
    if not positive:
        return -2, 0
    low = math.floor(math.log10(min(positive)))
    high = math.ceil(math.log10(max(positive)))
    return low, max(high, low + 1)


def _tokens_label(value: float) -> str:
    for size, suffix in ((1e9, "G"), (1e6, "M"), (1e3, "k")):
        if value >= size:
            return f"{value / size:g}{suffix}"
    return f"{value:g}"


def cost_box_plot(sets: list[ResultSet]) -> str:
    """Per-task cost, one box per result set, log axis: min–max whiskers, Q1–Q3 box, median bar,
    mean diamond (the paper's figure). USD when any task is priced, else tokens per task."""
    in_usd = any(r.cost_usd is not None for rs in sets for r in rs.rows)
    attribute = "cost_usd" if in_usd else "total_tokens"
    values = [[v for r in rs.rows if (v := getattr(r, attribute)) is not None] for rs in sets]
    label = (lambda v: "$" + _fmt(v)) if in_usd else _tokens_label
    title = (
        "API cost per task (USD, log scale)"
        if in_usd
        else "Tokens per task (input + output, log scale): no task has a priced model"
    )
    low, high = _decades([v for vs in values for v in vs])
    height = M_TOP + BOX_ROW * len(sets) + M_BOTTOM
    right = BOX_W - M_RIGHT

    def sx(v: float) -> float:
        v = max(v, 10.0**low)  # a zero cost sits on the axis's left edge
        return BOX_LEFT + (math.log10(v) - low) / (high - low) * (right - BOX_LEFT)

    parts = [
        f'<svg id="plot-compare-cost" class="plot" xmlns="http://www.w3.org/2000/svg" '
        f'width="{BOX_W}" height="{height}" viewBox="0 0 {BOX_W} {height}" role="img" '
        f'aria-label="{escape(title)}">',
        f'<text x="{BOX_W / 2}" y="18" text-anchor="middle" class="title">{escape(title)}</text>',
    ]
    bottom = height - M_BOTTOM
    for decade in range(low, high + 1):
        x = sx(10.0**decade)
        parts.append(f'<line class="grid" x1="{x:.1f}" x2="{x:.1f}" y1="{M_TOP}" y2="{bottom}"/>')
        parts.append(
            f'<text x="{x:.1f}" y="{bottom + 16}" text-anchor="middle">{label(10.0**decade)}</text>'
        )
    parts.append(f'<line class="axis" x1="{BOX_LEFT}" x2="{right}" y1="{bottom}" y2="{bottom}"/>')
    parts.append(
        f'<text x="{(BOX_LEFT + right) / 2}" y="{height - 12}" text-anchor="middle">'
        f"{'USD per task' if in_usd else 'tokens per task'}</text>"
    )
    for i, (rs, vs) in enumerate(zip(sets, values, strict=True)):
        y = M_TOP + BOX_ROW * i + BOX_ROW / 2
        unpriced = len(rs.rows) - len(vs)
        note = f"n={len(vs)}" + (
            f", {unpriced} without a {'price' if in_usd else 'costs.json'}" if unpriced else ""
        )
        parts.append(
            f'<text x="{BOX_LEFT - 8}" y="{y - 2:.1f}" text-anchor="end" class="set">'
            f"{escape(rs.name)}</text>"
            f'<text x="{BOX_LEFT - 8}" y="{y + 12:.1f}" text-anchor="end" class="note">'
            f"{note}</text>"
        )
        if not vs:
            parts.append(
                f'<text class="empty" x="{BOX_LEFT + 8}" y="{y + 4:.1f}">'
                f"{'no priced task' if in_usd else 'no costs.json'}</text>"
            )
            continue
        q1, q3 = quartiles(vs)
        tip = (
            f"{rs.name}: median {label(median(vs))}, mean {label(mean(vs))}, "
            f"Q1 {label(q1)}, Q3 {label(q3)}, min {label(min(vs))}, max {label(max(vs))}; {note}"
        )
        low_x, q1_x, mid_x, q3_x, high_x, mean_x = (
            sx(v) for v in (min(vs), q1, median(vs), q3, max(vs), mean(vs))
        )
        parts.append(
            f'<g class="mark box" data-set="{escape(rs.name)}"><title>{escape(tip)}</title>'
            f'<path class="whisker" d="M{low_x:.1f},{y:.1f}H{high_x:.1f}'
            f"M{low_x:.1f},{y - 7:.1f}v14M{high_x:.1f},{y - 7:.1f}v14"
            f'" stroke="{GREY}" fill="none"/>'
            f'<rect x="{q1_x:.1f}" y="{y - 12:.1f}" width="{max(q3_x - q1_x, 1):.1f}" '
            f'height="24" fill="#fff" stroke="#333"/>'
            f'<line class="median" x1="{mid_x:.1f}" x2="{mid_x:.1f}" y1="{y - 12:.1f}" '
            f'y2="{y + 12:.1f}" stroke="{set_color(i)}" stroke-width="4"/>'
            f'<path class="mean" d="M{mean_x:.1f},{y - 5:.1f}l5,5l-5,5l-5,-5z" '
            f'fill="#fff" stroke="#333"/></g>'
        )
    parts.append("</svg>")
    return "\n".join(parts)


def _html_table(table_id: str, header: list[str], lines: list[list[str]]) -> str:
    """A table whose first column names the result set, with its colour."""
    head = "".join(f"<th>{escape(h)}</th>" for h in header)
    body = "".join(
        f"<tr><th>{_swatch(i)}{escape(line[0])}</th>"
        + "".join(f"<td>{escape(c)}</td>" for c in line[1:])
        + "</tr>"
        for i, line in enumerate(lines)
    )
    return f'<table id="{table_id}"><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>'


def _unpriced_note(sets: list[ResultSet]) -> str:
    models = unpriced_models(sets)
    if not models:
        return ""
    return f'<p class="note">No price in the config for model(s): {escape(", ".join(models))}</p>'


def _timely_note(window: float) -> str:
    return (
        f'<p class="note">Timely: a targeted task passed with a reaction time of at most '
        f"{window:g} s, from the condition to the first contact of either kind; timely rates "
        "leave no-ops out. Times are the run's simulated seconds ÷ its speed factor: wall "
        "seconds on a live clock.</p>"
    )


def render_comparison_report(
    sets: list[ResultSet],
    window: float,
    links: TranscriptLinks | None = None,
    site: str | None = None,
) -> str:
    summaries = [(rs, summarise(rs.rows, window)) for rs in sets]
    names = " vs ".join(rs.name for rs in sets)
    success = _html_table("success", *success_table(summaries))
    timely = _html_table("timely", *timely_table(summaries))
    axes = _html_table("axes", *axis_table(sets, window))
    timely_axes = _html_table("timely-axes", *axis_table(sets, window, timely=True))
    cost = _html_table("cost", *cost_table(summaries))
    tools = _html_table("tool-calls", *tool_calls_table(summaries))
    reaction = _html_table(
        "reaction",
        ["result set", "n", "mean (s)", "median (s)"],
        [
            [rs.name, str(len(s.reaction)), _opt(mean(s.reaction)), _opt(median(s.reaction))]
            for rs, s in summaries
        ],
    )
    plots = [comparison_success_plot(sets, window), cost_box_plot(sets)]
    legend = " ".join(
        f"{_swatch(i)}{escape(rs.name)} (clock: {escape(clocks(rs.rows))})"
        for i, rs in enumerate(sets)
    )
    return (
        '<!doctype html>\n<html lang="en"><head><meta charset="utf-8">'
        f"<title>Benchmark comparison: {escape(names)}</title>"
        f"<style>{STYLE}{SECTION_STYLE}</style></head><body>"
        f"<h1>Benchmark comparison: {escape(names)}</h1>"
        f"{''.join(manifest_section(rs) for rs in sets)}"
        f'<p class="legend">{legend}</p>{_timely_note(window)}'
        f"{differences_section(sets, window)}"
        f"<h2>Success by category</h2>{success}"
        f"<h2>Timely success by category</h2>{timely}"
        f"<h2>Success by persistence and criteria</h2>{axes}"
        f"<h2>Timely success by persistence and criteria</h2>{timely_axes}"
        f'<div class="plots">{"".join(plots)}</div>'
        f"<h2>Cost per task (USD)</h2>{cost}{_unpriced_note(sets)}"
        f"<h2>Tool calls per task</h2>{tools}"
        f"<h2>Reaction time (passed targeted tasks)</h2>{reaction}"
        f"{''.join(errors_section(rs) for rs in sets)}"
        f"{''.join(reports_section(rs) for rs in sets)}"
        f"<h2>Per task</h2>{tasks_table(sets, window, links or {}, site)}"
        "</body></html>\n"
    )


# --- per task, with transcripts --------------------------------------------------------------


def _opt(value: float | None, fmt: str = "{:.1f}") -> str:
    return "" if value is None else fmt.format(value)


TASK_COLUMNS = (
    "task",
    "environment",
    "agent",
    "category",
    "success",
    "timely",
    "reaction (s)",
    "cost (USD)",
    "tool calls",
)


def task_facts(set_name: str, row: Row, window: float) -> list[tuple[str, str]]:
    """A task's cells in the per-task table (TASK_COLUMNS), as (label, value) pairs."""
    values = (
        row.label,
        row.environment,
        set_name,
        f"{row.category}, {row.persistence}, {row.criteria}",  # the paper's and its future axes
        "yes" if row.success else "no",
        "n/a" if row.is_noop else "yes" if row.timely(window) else "no",
        _opt(row.reaction_time),
        _opt(row.cost_usd, "${:.4f}"),
        "" if row.tool_calls is None else str(row.tool_calls),
    )
    return list(zip(TASK_COLUMNS, values, strict=True))


def tasks_table(
    sets: list[ResultSet], window: float, links: TranscriptLinks, site: str | None = None
) -> str:
    """Every task of every set, a task's sets next to each other, linked to its transcript and
    to its timeline in the admin of `site` (apps.bench.timeline_links)."""
    entries = sorted(
        (
            (row.environment, row.label, i, rs.name, row)
            for i, rs in enumerate(sets)
            for row in rs.rows
        ),
        key=lambda e: e[:3],
    )
    body = []
    for environment, name, i, set_name, row in entries:
        facts = task_facts(set_name, row, window)
        cells = "".join(
            f"<td>{_swatch(i) if label == 'agent' else ''}{escape(value)}</td>"
            for label, value in facts
        )
        href = links.get((set_name, environment, name))
        link = f'<a class="transcript" href="{href}">transcript</a>' if href else "none"
        timeline = (
            f'<a class="timeline" href="{escape(timeline_url(site, row.run))}">timeline</a>'
            if row.run is not None
            else "none"
        )
        body.append(
            f'<tr class="{"ok" if row.success else "fail"}">{cells}<td>{timeline}</td>'
            f"<td>{link}</td></tr>"
        )
    head = "".join(f"<th>{escape(h)}</th>" for h in (*TASK_COLUMNS, "timeline", "transcript"))
    return f'<table id="tasks"><thead><tr>{head}</tr></thead><tbody>{"".join(body)}</tbody></table>'


def transcripts_folder(report: Path) -> Path:
    return report.with_name(f"{report.stem}-transcripts")


def write_transcripts(report: Path, sets: list[ResultSet], window: float) -> TranscriptLinks:
    """A page per task that has a transcript, beside the report; the report's links to them."""
    report.parent.mkdir(parents=True, exist_ok=True)
    links: TranscriptLinks = {}
    for rs in sets:
        for row in rs.rows:
            if not has_transcript(row.folder):
                continue
            stem = row.name if row.trial == 1 else f"{row.name}-trial-{row.trial}"
            page = transcripts_folder(report) / rs.name / row.environment / f"{stem}.html"
            page.parent.mkdir(parents=True, exist_ok=True)
            facts = task_facts(rs.name, row, window)
            facts.append(("verdict", str(row.result.get("detail") or "")))
            page.write_text(
                render_transcript_page(
                    title=f"{row.label} — {rs.name}",
                    facts=facts,
                    task_folder=row.folder,
                    page_folder=page.parent,
                    back_href=relative_href(report, page.parent),
                ),
                encoding="utf-8",
            )
            links[(rs.name, row.environment, row.label)] = relative_href(page, report.parent)
    return links
