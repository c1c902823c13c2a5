"""An inline SVG timeline: the scenario's events over time, condition_at and kill_at marked.

Drawn on the server (no JavaScript, no static files). When a dry run is given, events after which
the eval condition holds are drawn filled green, the others hollow.
"""

from __future__ import annotations

from django.utils.html import format_html, format_html_join
from django.utils.safestring import SafeString

WIDTH, HEIGHT, LEFT, RIGHT, AXIS_Y = 860, 150, 40, 20, 100


def timeline_svg(scenario, events, dry_run=None) -> SafeString:
    times = [e.time for e in events]
    horizon = max([scenario.event_timeline_end or 0, scenario.kill_at or 0, *times, 1.0])
    span = WIDTH - LEFT - RIGHT

    def x(t: float) -> float:
        return round(LEFT + span * max(t, 0.0) / horizon, 1)

    holds = {}
    if dry_run is not None:
        holds = {step.position: step.holds for step in dry_run.steps}
    step = 60 if horizon <= 1200 else 300
    ticks = format_html_join(
        "",
        '<line x1="{0}" y1="{1}" x2="{0}" y2="{2}" stroke="#999"/><text x="{0}" y="{3}" font-size="10" '
        'text-anchor="middle" fill="#555">{4}</text>',
        (
            (x(t), AXIS_Y, AXIS_Y + 4, AXIS_Y + 16, f"{t:g}s")
            for t in range(0, int(horizon) + 1, step)
        ),
    )
    marks = format_html_join(
        "",
        '<g class="event"><title>#{0} {1} s · {2}</title><circle cx="{3}" cy="{4}" r="5" fill="{5}" '
        'stroke="#1f5fa8" stroke-width="1.5"/></g>',
        (
            (
                e.position,
                f"{e.time:g}",
                e.type,
                x(e.time),
                AXIS_Y - 12 - 10 * (i % 3),
                "#2e9b4a" if holds.get(e.position) else ("#fff" if holds else "#1f5fa8"),
            )
            for i, e in enumerate(events)
        ),
    )
    lines = []
    if scenario.condition_at is not None:
        lines.append(
            (
                "condition-at",
                x(scenario.condition_at),
                "#c0392b",
                f"condition_at {scenario.condition_at:g} s",
                14,
            )
        )
    if scenario.kill_at is not None:
        lines.append(
            ("kill-at", x(scenario.kill_at), "#333", f"kill_at {scenario.kill_at:g} s", 28)
        )
    if dry_run is not None and dry_run.first_holds_at is not None:
        lines.append(
            (
                "holds-at",
                x(dry_run.first_holds_at),
                "#2e9b4a",
                f"holds from {dry_run.first_holds_at:g} s",
                42,
            )
        )
    markers = format_html_join(
        "",
        '<g class="{0}"><line x1="{1}" y1="8" x2="{1}" y2="{5}" stroke="{2}" stroke-width="2" '
        'stroke-dasharray="5 3"/><text x="{1}" y="{4}" dx="4" font-size="11" fill="{2}">{3}</text></g>',
        ((cls, pos, color, label, y, AXIS_Y) for cls, pos, color, label, y in lines),
    )
    return format_html(
        '<svg id="timeline-chart" xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" '
        'viewBox="0 0 {0} {1}" role="img" aria-label="Scenario timeline: {2} events over {3} s">'
        '<line x1="{4}" y1="{5}" x2="{6}" y2="{5}" stroke="#333"/>{7}{8}{9}</svg>',
        WIDTH,
        HEIGHT,
        len(events),
        f"{horizon:g}",
        LEFT,
        AXIS_Y,
        WIDTH - RIGHT,
        ticks,
        markers,
        marks,
    )
