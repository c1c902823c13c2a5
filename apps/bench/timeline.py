"""One task on one clock: what the world did and what the agent did, on the run's simulated axis.

`build_timeline(trace)` (pure) sets side by side, in simulated seconds:

- the world: the scenario's entries as they fired — the trigger (at `condition_at`) and the
  distractors —, `condition_at`, the reaction window after it and `kill_at`;
- the agent as the run logged it: page views, actions, fast-forward skips, its contact;
- the agent as its transcript says (when it wrote one): each model call with its tokens, the
  tool it chose spanning until the tool returned, and each question wait_for's judge was asked,
  with the diff blocks it was shown and its answer.

`render_timeline(timeline, links)` draws it as one inline SVG axis (no script) and a list in time
order below, each row a <details> holding its screenshot, what the model saw or was shown, and
a link to the site as it was at that moment (time travel at that log position). `links` says
where those live (the admin's URLs), so the page is the same wherever it is served.
"""

from __future__ import annotations

import bisect
import json
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from html import escape
from typing import Any
from urllib.parse import urlsplit

from apps.bench.report import nice_ticks
from apps.bench.task_trace import DISTRACTOR, PRELOAD, TRIGGER, LogEntry, TaskTrace
from apps.bench.transcripts import Step

WORLD, LOGGED, MODEL = "world", "agent (log)", "agent (transcript)"
LANES = (WORLD, LOGGED, MODEL)
CONTACTS = ("contact_get", "contact_post")
SHOWN_LIFECYCLE = ("start", "skip", *CONTACTS)
TEXT_LIMIT = 4000  # characters of a result or an observation shown in a row
# Moments drawn and listed: an agent that floods its log (up to SENTINEL_AGENT_LOG_BUDGET
# entries) must not make a page of tens of thousands of rows; the run's whole log pages them.
MAX_SHOWN = 2000


@dataclass(frozen=True)
class Entry:
    """One moment (or span) of the timeline: a mark on the axis and a row of the list."""

    at: float
    lane: str
    kind: str  # trigger, distractor | view, action, skip, start, contact | model, check
    title: str
    until: float | None = None  # a span's end (a tool call, a skip)
    seq: int | None = None  # the log position "the site at this moment" shows
    page: str = ""  # the page it shows: a path under the environment's root
    screenshot: str | None = None  # relative to the agent's files (`agent/` in the task folder)
    tokens: tuple[int, int] | None = None  # (input, output)
    text: str = ""  # what the row holds when expanded
    blocks: tuple[str, ...] = ()  # a judge question's diff blocks
    answer: str = ""  # a judge's answer


@dataclass(frozen=True)
class Verdict:
    success: bool | None  # None: not graded
    detail: str  # the grading query's result, as the verdict says it
    reaction_time: float | None  # wall seconds (results.json)
    reaction_sim: float | None  # simulated seconds from condition_at to the first contact
    eval_sql: str


@dataclass(frozen=True)
class Timeline:
    title: str
    start: float
    end: float
    condition_at: float | None
    window_end: float | None
    kill_at: float | None
    contact_at: float | None
    speed_factor: float
    verdict: Verdict
    entries: list[Entry] = field(default_factory=list)
    has_transcript: bool = False


# --- building --------------------------------------------------------------------------------


class LogPositions:
    """The log position showing simulated second `at`: the last entry logged at or before it."""

    def __init__(self, log: list[LogEntry]) -> None:
        self.seqs = [entry.seq for entry in log]
        self.ats: list[float] = []
        latest = 0.0
        for entry in log:  # a running maximum: bisect needs them sorted
            latest = max(latest, entry.at)
            self.ats.append(latest)

    def at(self, moment: float | None) -> int | None:
        if moment is None or not self.seqs:
            return None
        index = bisect.bisect_right(self.ats, moment + 1e-9) - 1
        return self.seqs[max(index, 0)]


def environment_page(url: str | None, root: str) -> str:
    """A URL or logged path (/r/<token>/<env>/x?y) as a page under the environment (x?y)."""
    if not url:
        return ""
    parts = urlsplit(url)
    path = parts.path + (f"?{parts.query}" if parts.query else "")
    prefix = root.rstrip("/") + "/"
    return path[len(prefix) :] if root and path.startswith(prefix) else ""


def _world(trace: TaskTrace) -> list[Entry]:
    entries = []
    for entry in trace.log:
        role = trace.role(entry)
        if role is None or role == PRELOAD:
            continue
        what = ", ".join(f"{k}={v}" for k, v in entry.payload.items() if not isinstance(v, list))
        entries.append(
            Entry(
                at=entry.at,
                lane=WORLD,
                kind=role,
                title=f"{'trigger' if role == TRIGGER else 'event'}: {entry.type} {what}".strip(),
                seq=entry.seq,
                text=json.dumps(dict(entry.payload), ensure_ascii=False),
            )
        )
    return entries


def _logged(trace: TaskTrace, root: str) -> list[Entry]:
    entries = []
    for entry in trace.log:
        payload = entry.payload
        if entry.kind == "view":
            path = str(payload.get("path", ""))
            page = environment_page(path, root)
            entries.append(
                Entry(entry.at, LOGGED, "view", f"page view /{page}", seq=entry.seq, page=page)
            )
        elif entry.kind == "action":
            args = json.dumps(dict(payload), ensure_ascii=False)
            entries.append(
                Entry(entry.at, LOGGED, "action", f"action {entry.type} {args}", seq=entry.seq)
            )
        elif entry.kind == "lifecycle" and entry.type in SHOWN_LIFECYCLE:
            if entry.type == "skip":
                until = float(payload.get("to", entry.at))
                title = f"skip to {until:.1f} s ({payload.get('why', '')})"
                entries.append(Entry(entry.at, LOGGED, "skip", title, until=until, seq=entry.seq))
            elif entry.type in CONTACTS:
                message = payload.get("message")
                title = "contact" + (f": {message}" if message else f" ({entry.type})")
                entries.append(Entry(entry.at, LOGGED, "contact", title, seq=entry.seq))
            else:
                entries.append(Entry(entry.at, LOGGED, "start", "task opened", seq=entry.seq))
    return entries


def _tokens(usage: Any) -> tuple[int, int] | None:
    if not isinstance(usage, Mapping):
        return None
    counts = [usage.get("input_tokens"), usage.get("output_tokens")]
    if not all(isinstance(c, int) for c in counts):
        return None
    return counts[0], counts[1]


def _as_text(value: Any) -> str:
    text = value if isinstance(value, str) else json.dumps(value, ensure_ascii=False)
    return text if len(text) <= TEXT_LIMIT else text[:TEXT_LIMIT] + " …"


def _transcript(steps: list[Step], positions: LogPositions, root: str) -> list[Entry]:
    entries = []
    for step in steps:
        at = step.sim_start if step.sim_start is not None else step.sim_time
        if at is None:
            continue  # a step with no simulated time has no place on the axis
        page = environment_page(step.url, root)
        arguments = "" if step.arguments in (None, {}) else _as_text(step.arguments)
        call = f"{step.tool}({arguments})" if step.tool else "no tool call"
        parts = [f"result: {_as_text(step.result)}"] if step.result not in (None, "") else []
        if step.text:
            parts.insert(0, f"model: {_as_text(step.text)}")
        if step.observation:
            parts.append(f"page as the model read it:\n{_as_text(step.observation)}")
        entries.append(
            Entry(
                at=at,
                lane=MODEL,
                kind="model",
                title=f"step {step.number}: model call → {call}",
                until=step.sim_time,
                seq=positions.at(at),
                page=page,
                screenshot=step.screenshot if isinstance(step.screenshot, str) else None,
                tokens=_tokens(step.usage),
                text="\n\n".join(parts),
            )
        )
        for number, check in enumerate(step.checks or [], start=1):
            if not isinstance(check, Mapping) or not isinstance(check.get("sim_time"), int | float):
                continue
            blocks = tuple(str(b) for b in check.get("blocks") or [])
            met = check.get("met")
            entries.append(
                Entry(
                    at=float(check["sim_time"]),
                    lane=MODEL,
                    kind="check",
                    title=f"step {step.number}: wait_for asks the model ({number}): "
                    f"{len(blocks)} change{'s' if len(blocks) != 1 else ''} shown → "
                    f"{'met' if met else 'not met'}",
                    seq=positions.at(float(check["sim_time"])),
                    page=page,
                    tokens=_tokens(check.get("usage")),
                    blocks=blocks,
                    answer=str(check.get("why") or ""),
                )
            )
    return entries


def _verdict(trace: TaskTrace, recorded: Mapping[str, Any] | None, contact_at: float | None):
    result = trace.result or {}
    success = result.get("success", (recorded or {}).get("success"))
    detail = result.get("detail") or (recorded or {}).get("detail") or "not graded yet"
    condition = trace.condition_at
    reaction_sim = (
        contact_at - condition if contact_at is not None and condition is not None else None
    )
    reaction = result.get("reaction_time")
    return Verdict(
        success=success if isinstance(success, bool) else None,
        detail=str(detail),
        reaction_time=float(reaction) if isinstance(reaction, int | float) else None,
        reaction_sim=reaction_sim,
        eval_sql=str(trace.scenario.get("eval_sql") or ""),
    )


def build_timeline(
    trace: TaskTrace,
    *,
    title: str,
    environment_root: str,
    window: float,
    recorded: Mapping[str, Any] | None = None,
) -> Timeline:
    """The task's timeline; `environment_root` is the run's /r/<token>/<env> (to read pages
    off logged paths and transcript URLs), `window` the reaction window in wall seconds,
    `recorded` a verdict recorded for the run when the task has no results.json."""
    positions = LogPositions(trace.log)
    contacts = [e.at for e in trace.log if e.kind == "lifecycle" and e.type in CONTACTS]
    contact_at = contacts[0] if contacts else None
    entries = [
        *_world(trace),
        *_logged(trace, environment_root),
        *_transcript(trace.steps, positions, environment_root),
    ]
    order = {lane: n for n, lane in enumerate(LANES)}
    entries.sort(key=lambda e: (e.at, order[e.lane]))
    condition = trace.condition_at
    kill_at = trace.scenario.get("kill_at")
    kill_at = float(kill_at) if isinstance(kill_at, int | float) else None
    window_end = None if condition is None else condition + window * trace.speed_factor
    moments = [e.until or e.at for e in entries] + [
        m for m in (condition, window_end, kill_at) if m is not None
    ]
    return Timeline(
        title=title,
        start=0.0,
        end=max([1.0, *moments]),
        condition_at=condition,
        window_end=window_end,
        kill_at=kill_at,
        contact_at=contact_at,
        speed_factor=trace.speed_factor,
        verdict=_verdict(trace, recorded, contact_at),
        entries=entries,
        has_transcript=bool(trace.steps),
    )


# --- rendering -------------------------------------------------------------------------------


@dataclass(frozen=True)
class Links:
    """Where the page's links go: time travel at a log position and page, a screenshot."""

    site_at: Callable[[int, str], str]
    screenshot: Callable[[str], str]


WIDTH, LEFT, RIGHT = 1200, 130, 20
LANE_Y = {WORLD: 46, LOGGED: 96, MODEL: 146}
HEIGHT = 186
COLORS = {
    TRIGGER: "#c8322d",
    DISTRACTOR: "#8a8a8a",
    "view": "#1f6fb4",
    "action": "#e07b00",
    "skip": "#9bb7d4",
    "start": "#555",
    "contact": "#2a9d4b",
    "model": "#8e44ad",
    "check": "#d35ec8",
}

STYLE = """
.tl-facts{display:grid;grid-template-columns:max-content 1fr;gap:2px 14px;margin:0 0 12px}
.tl-facts dt{color:#666} .tl-facts dd{margin:0}
.tl-pass{color:#2a9d4b;font-weight:600} .tl-fail{color:#c8322d;font-weight:600}
#tl-axis{width:100%;height:auto;border:1px solid #ddd;background:#fff;margin:8px 0}
#tl-axis text{font:11px system-ui,sans-serif;fill:#333} #tl-axis .lane{fill:#555;font-weight:600}
#tl-legend span{display:inline-block;margin-right:14px;font-size:12px}
#tl-legend i{display:inline-block;width:10px;height:10px;margin-right:4px;border-radius:2px}
#tl-list{list-style:none;padding:0;margin:8px 0}
#tl-list li{border-top:1px solid #eee;padding:3px 0;margin:0}
#tl-list summary{cursor:pointer;font-size:13px}
#tl-list .when{display:inline-block;width:8.5em;font-variant-numeric:tabular-nums;color:#444}
#tl-list .lane{display:inline-block;width:10em;color:#777;font-size:12px}
#tl-list .dot{display:inline-block;width:9px;height:9px;border-radius:50%;margin-right:6px}
#tl-list .kind-trigger summary{font-weight:700;color:#c8322d}
#tl-list .tokens{color:#777;font-size:12px;margin-left:8px}
#tl-list .body{padding:6px 0 8px 8.5em;display:flex;gap:16px;align-items:flex-start}
#tl-list .body pre{white-space:pre-wrap;font-size:12px;background:#f6f6f6;padding:6px;margin:4px 0;
  max-height:360px;overflow:auto}
#tl-list .body .text{flex:1;min-width:0}
#tl-list img.screenshot{max-width:640px;border:1px solid #ccc}
#tl-list .block{border-left:3px solid #d35ec8}
"""


def _x(timeline: Timeline, at: float) -> float:
    span = max(timeline.end - timeline.start, 1e-9)
    return LEFT + (at - timeline.start) / span * (WIDTH - LEFT - RIGHT)


def _mark(timeline: Timeline, index: int, entry: Entry) -> str:
    x, y = _x(timeline, entry.at), LANE_Y[entry.lane]
    color = COLORS.get(entry.kind, "#333")
    tip = f"<title>{entry.at:.1f} s · {escape(entry.title[:200])}</title>"
    if entry.kind == TRIGGER:
        shape = (
            f'<path d="M{x:.1f},{y - 11} l9,11 l-9,11 l-9,-11 z" fill="{color}"/>'
            f'<text x="{x + 11:.1f}" y="{y - 10}" fill="{color}">trigger</text>'
        )
    elif entry.until is not None and entry.until > entry.at:
        x2 = _x(timeline, entry.until)
        band = 8 if entry.kind == "skip" else 12
        shape = (
            f'<rect x="{x:.1f}" y="{y - band / 2}" width="{max(x2 - x, 2):.1f}" height="{band}" '
            f'fill="{color}" fill-opacity="{0.5 if entry.kind == "skip" else 0.35}"/>'
        )
        if entry.kind == "model":
            shape += f'<circle cx="{x:.1f}" cy="{y}" r="5" fill="{color}"/>'
    elif entry.kind == "check":
        shape = f'<path d="M{x:.1f},{y + 4} l6,10 l-12,0 z" fill="{color}"/>'
    elif entry.kind == "contact":
        shape = (
            f'<rect x="{x - 5:.1f}" y="{y - 9}" width="10" height="18" fill="{color}"/>'
            f'<text x="{x + 8:.1f}" y="{y - 10}" fill="{color}">contact</text>'
        )
    elif entry.kind == DISTRACTOR:
        shape = f'<rect x="{x - 1.5:.1f}" y="{y - 7}" width="3" height="14" fill="{color}"/>'
    else:
        shape = f'<circle cx="{x:.1f}" cy="{y}" r="4" fill="{color}"/>'
    return f'<a href="#tl-{index}" class="mark kind-{entry.kind}">{tip}{shape}</a>'


def _vertical(timeline: Timeline, at: float, label: str, color: str, dash: str = "") -> str:
    x = _x(timeline, at)
    style = f' stroke-dasharray="{dash}"' if dash else ""
    # A label near the right edge reads leftwards, so it is never cut off.
    anchor = ' text-anchor="end"' if x > WIDTH - 120 else ""
    shift = -3 if anchor else 3
    return (
        f'<line x1="{x:.1f}" x2="{x:.1f}" y1="16" y2="{HEIGHT - 22}" stroke="{color}"{style}/>'
        f'<text x="{x + shift:.1f}" y="14" fill="{color}"{anchor}>{escape(label)}</text>'
    )


def render_axis(timeline: Timeline) -> str:
    parts = [
        f'<svg id="tl-axis" viewBox="0 0 {WIDTH} {HEIGHT}" role="img" '
        f'aria-label="the task on the run\'s simulated clock">'
    ]
    if timeline.condition_at is not None and timeline.window_end is not None:
        x1, x2 = _x(timeline, timeline.condition_at), _x(timeline, timeline.window_end)
        parts.append(
            f'<rect id="tl-window" x="{x1:.1f}" y="18" width="{max(x2 - x1, 1):.1f}" '
            f'height="{HEIGHT - 40}" fill="#2a9d4b" fill-opacity="0.08">'
            "<title>the reaction window</title></rect>"
        )
    for lane, y in LANE_Y.items():
        parts.append(
            f'<line x1="{LEFT}" x2="{WIDTH - RIGHT}" y1="{y}" y2="{y}" stroke="#e4e4e4"/>'
            f'<text class="lane" x="6" y="{y + 4}">{escape(lane)}</text>'
        )
    for tick in nice_ticks(timeline.start, timeline.end, 10):
        if timeline.start <= tick <= timeline.end:
            x = _x(timeline, tick)
            parts.append(
                f'<line x1="{x:.1f}" x2="{x:.1f}" y1="{HEIGHT - 22}" y2="{HEIGHT - 17}" '
                f'stroke="#999"/><text x="{x:.1f}" y="{HEIGHT - 5}" text-anchor="middle">'
                f"{tick:g} s</text>"
            )
    if timeline.condition_at is not None:
        parts.append(_vertical(timeline, timeline.condition_at, "condition_at", "#c8322d", "4 3"))
    if timeline.kill_at is not None:
        parts.append(_vertical(timeline, timeline.kill_at, "kill_at", "#333", "2 3"))
    shown = timeline.entries[:MAX_SHOWN]
    parts += [_mark(timeline, n, entry) for n, entry in enumerate(shown)]
    parts.append("</svg>")
    return "".join(parts)


def _legend() -> str:
    names = {
        TRIGGER: "trigger",
        DISTRACTOR: "other event (distractor)",
        "view": "page view",
        "action": "action",
        "skip": "fast-forward skip",
        "contact": "contact",
        "model": "model call → tool (span: until it returned)",
        "check": "wait_for asks the model",
    }
    return (
        '<p id="tl-legend">'
        + "".join(
            f'<span><i style="background:{COLORS[k]}"></i>{v}</span>' for k, v in names.items()
        )
        + '<span><i style="background:#2a9d4b;opacity:.2"></i>reaction window</span></p>'
    )


def _facts(timeline: Timeline) -> str:
    verdict = timeline.verdict
    if verdict.success is None:
        outcome = "not graded"
    else:
        outcome = (
            '<span class="tl-pass">pass</span>'
            if verdict.success
            else '<span class="tl-fail">fail</span>'
        )
    if verdict.reaction_time is not None or verdict.reaction_sim is not None:
        wall = f"{verdict.reaction_time:.1f} s" if verdict.reaction_time is not None else "—"
        sim = f"{verdict.reaction_sim:.1f} s" if verdict.reaction_sim is not None else "—"
        reaction = f"{wall} (simulated {sim})"
    else:
        reaction = "— (no contact, or no condition)"

    def seconds(value: float | None, none: str) -> str:
        return none if value is None else f"{value:.1f} s"

    rows = [
        ("verdict", outcome),
        ("reaction time", escape(reaction)),
        ("grading query", f"<code>{escape(verdict.detail)}</code>"),
        ("condition_at", seconds(timeline.condition_at, "— (no-op)")),
        ("contact", seconds(timeline.contact_at, "none")),
        ("kill_at", seconds(timeline.kill_at, "—")),
        ("clock", f"simulated seconds; speed factor {timeline.speed_factor:g}"),
    ]
    facts = "".join(f"<dt>{k}</dt><dd>{v}</dd>" for k, v in rows)
    sql = (
        f"<details><summary>eval_sql</summary><pre>{escape(verdict.eval_sql)}</pre></details>"
        if verdict.eval_sql
        else ""
    )
    return f'<dl class="tl-facts" id="tl-verdict">{facts}</dl>{sql}'


def _row(index: int, entry: Entry, links: Links) -> str:
    when = f"{entry.at:.1f} s"
    if entry.until is not None and entry.until > entry.at:
        when = f"{entry.at:.1f}–{entry.until:.1f} s"
    tokens = (
        f'<span class="tokens">{entry.tokens[0]} in, {entry.tokens[1]} out tokens</span>'
        if entry.tokens
        else ""
    )
    summary = (
        f'<span class="when">{when}</span><span class="lane">{escape(entry.lane)}</span>'
        f'<span class="dot" style="background:{COLORS.get(entry.kind, "#333")}"></span>'
        f"{escape(entry.title[:300])}{tokens}"
    )
    texts = []
    if entry.text:
        texts.append(f"<pre>{escape(entry.text)}</pre>")
    if entry.blocks:
        texts.append("<p>changes shown to the model:</p>")
        texts += [f'<pre class="block">{escape(block)}</pre>' for block in entry.blocks]
        texts.append(f"<p>its answer: {escape(entry.answer)}</p>")
    if entry.seq is not None:
        texts.append(
            f'<p><a class="site-at" href="{escape(links.site_at(entry.seq, entry.page))}">'
            f"the site at this moment</a> (log position #{entry.seq})</p>"
        )
    shot = ""
    if entry.screenshot:
        src = escape(links.screenshot(entry.screenshot))
        shot = f'<a href="{src}"><img class="screenshot" loading="lazy" src="{src}" alt="screenshot"></a>'
    return (
        f'<li id="tl-{index}" class="kind-{entry.kind}" data-at="{entry.at:.3f}">'
        f"<details><summary>{summary}</summary>"
        f'<div class="body"><div class="text">{"".join(texts)}</div>{shot}</div>'
        "</details></li>"
    )


def render_timeline(timeline: Timeline, links: Links) -> str:
    """The page's content (without the admin's chrome): facts, axis, legend, list."""
    note = (
        ""
        if timeline.has_transcript
        else "<p>No transcript: the agent's side is what the run logged.</p>"
    )
    rows = "".join(_row(n, e, links) for n, e in enumerate(timeline.entries[:MAX_SHOWN]))
    left = len(timeline.entries) - MAX_SHOWN
    cut = (
        f'<p id="tl-cut">{left} later moments not shown (the first {MAX_SHOWN} are): the run\'s '
        "whole log lists them all.</p>"
        if left > 0
        else ""
    )
    return (
        f"<style>{STYLE}</style>{_facts(timeline)}{render_axis(timeline)}{_legend()}{note}"
        f'<ol id="tl-list">{rows}</ol>{cut}'
    )
