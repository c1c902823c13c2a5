"""An agent's transcript (`transcript.jsonl` among its files: `agent/` in its task folder),
rendered as one HTML page.

The reference agents write one JSON object per step — `{"step", "t", "sim_start", "sim_time",
"url", "text", "tool", "arguments", "result", "screenshot", "usage"}`, and `checks` on a
wait_for step (apps/browser_agent/transcript.py) — and the screenshots under `transcript/`. An
agent killed at its deadline can leave a half-written last line, and any agent may write what it
likes: every line that is not such an object is shown as unreadable, a jump in step numbers as
missing steps, a screenshot that is not there as missing; none of them stops the page.

Screenshots are linked by relative path into the results tree rather than copied or inlined, so
a report over hundreds of tasks costs no extra disk; the pages work when opened as files for as
long as the results tree stays where it was when the report was written.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from html import escape
from pathlib import Path
from typing import Any
from urllib.parse import quote

from apps.bench.layout import PROMPT, agent_files

TRANSCRIPT = "transcript.jsonl"
RAW_LINE_LIMIT = 2000  # characters of an unreadable line shown on the page
OPEN_RESULT_LIMIT = 600  # longer tool results start folded


@dataclass(frozen=True)
class Step:
    line: int
    number: int | None
    t: float | None
    url: str | None
    text: str | None
    tool: str | None
    arguments: Any
    result: Any
    screenshot: Any
    usage: Any
    sim_start: float | None = None  # the run's simulated time the model's page showed
    sim_time: float | None = None  # … and when the step ended
    checks: Any = None  # wait_for: its judge's questions
    observation: str | None = None  # the page's description the model read


@dataclass(frozen=True)
class Unreadable:
    line: int
    raw: str
    reason: str


def read_transcript(path: Path) -> list[Step | Unreadable]:
    """Every non-blank line of the file, as a step or as the reason it could not be one."""
    entries: list[Step | Unreadable] = []
    text = path.read_text(encoding="utf-8", errors="replace")
    for line, raw in enumerate(text.splitlines(), start=1):
        if not raw.strip():
            continue
        try:
            data = json.loads(raw)
        except json.JSONDecodeError as exc:
            entries.append(Unreadable(line, raw, f"not JSON ({exc.msg})"))
            continue
        if not isinstance(data, dict):
            entries.append(Unreadable(line, raw, "not a JSON object"))
            continue
        entries.append(
            Step(
                line=line,
                number=_number(data.get("step"), int),
                t=_number(data.get("t"), float),
                url=_text(data.get("url")),
                text=_text(data.get("text")),
                tool=_text(data.get("tool")),
                arguments=data.get("arguments"),
                result=data.get("result"),
                screenshot=data.get("screenshot"),
                usage=data.get("usage"),
                sim_start=_number(data.get("sim_start"), float),
                sim_time=_number(data.get("sim_time"), float),
                checks=data.get("checks"),
                observation=_text(data.get("observation")),
            )
        )
    return entries


def _number(value: Any, kind: type) -> Any:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    if kind is int and not float(value).is_integer():
        return None
    return kind(value)


def _text(value: Any) -> str | None:
    """A string field as itself; anything else (a number, a list) as its JSON."""
    if value is None or isinstance(value, str):
        return value
    return json.dumps(value)


def _as_text(value: Any) -> str:
    return value if isinstance(value, str) else json.dumps(value, indent=1, ensure_ascii=False)


def relative_href(target: Path, from_folder: Path) -> str:
    """A URL path from a page in `from_folder` to `target`, for links that work as files."""
    relative = os.path.relpath(os.path.abspath(target), os.path.abspath(from_folder))
    return quote(Path(relative).as_posix())


def _screenshot(value: Any, number: int | None, task_folder: Path, page_folder: Path) -> str:
    if value is None:
        return ""
    if not isinstance(value, str) or not value:
        return f'<p class="problem">screenshot: not a path: {escape(json.dumps(value))}</p>'
    target = task_folder / value
    if Path(value).is_absolute() or not target.resolve().is_relative_to(task_folder.resolve()):
        return f'<p class="problem">screenshot outside the task folder: {escape(value)}</p>'
    if not target.is_file():
        return f'<p class="problem">screenshot missing: {escape(value)}</p>'
    alt = f"screenshot of step {number}" if number is not None else "screenshot"
    return (
        f'<a href="{relative_href(target, page_folder)}">'
        f'<img class="screenshot" src="{relative_href(target, page_folder)}" alt="{alt}"></a>'
    )


def _usage(usage: Any) -> str:
    if usage is None:
        return ""
    if not isinstance(usage, dict):
        return f'<p class="problem">usage: {escape(json.dumps(usage))}</p>'
    counts = [
        f"{usage[key]} {label}"
        for key, label in (("input_tokens", "in"), ("output_tokens", "out"))
        if key in usage
    ]
    return f'<p class="usage">tokens: {escape(", ".join(counts) or "none reported")}</p>'


def _checks(checks: Any) -> str:
    """A wait_for step's judge questions: when, the diff blocks shown, the answer."""
    if not isinstance(checks, list) or not checks:
        return ""
    asked = []
    for check in checks:
        if not isinstance(check, dict):
            continue
        when = check.get("sim_time")
        when = f"sim {when:.1f} s" if isinstance(when, int | float) else "sim ?"
        blocks = "".join(f"<pre>{escape(str(b))}</pre>" for b in check.get("blocks") or [])
        answer = "met" if check.get("met") else "not met"
        asked.append(
            f'<li class="check"><p>{when}: {answer} — {escape(str(check.get("why") or ""))}</p>'
            f"{blocks}</li>"
        )
    return (
        f"<details><summary>wait_for asked the model {len(asked)} "
        f"time{'s' if len(asked) != 1 else ''}</summary><ol>{''.join(asked)}</ol></details>"
    )


def _step_html(step: Step, task_folder: Path, page_folder: Path) -> str:
    heading = f"Step {step.number}" if step.number is not None else f"Step ? (line {step.line})"
    when = (
        f' <span class="t" title="wall seconds since the agent started">t = {step.t:.1f} s</span>'
        if step.t is not None
        else ""
    )
    if step.sim_time is not None:
        when += f' <span class="t" title="the run\'s simulated clock">· sim {step.sim_time:.1f} s</span>'
    parts = [f'<section class="step" id="line-{step.line}"><div class="body">']
    parts.append(f"<h2>{escape(heading)}{when}</h2>")
    if step.url:
        parts.append(f'<p class="url"><code>{escape(step.url)}</code></p>')
    if step.text:
        parts.append(f'<div class="text">{escape(step.text)}</div>')
    if step.tool:
        parts.append(f'<p class="call">tool <code class="tool">{escape(step.tool)}</code></p>')
        if step.arguments not in (None, {}):
            parts.append(f'<pre class="arguments">{escape(_as_text(step.arguments))}</pre>')
    if step.result == "":
        parts.append('<p class="usage">empty result</p>')
    elif step.result is not None:
        result = _as_text(step.result)
        fold = "" if len(result) > OPEN_RESULT_LIMIT else " open"
        parts.append(
            f"<details{fold}><summary>result ({len(result)} characters)</summary>"
            f'<pre class="result">{escape(result)}</pre></details>'
        )
    parts.append(_checks(step.checks))
    parts.append(_usage(step.usage))
    parts.append("</div>")
    parts.append(_screenshot(step.screenshot, step.number, task_folder, page_folder))
    parts.append("</section>")
    return "".join(parts)


def _unreadable_html(entry: Unreadable) -> str:
    raw = entry.raw if len(entry.raw) <= RAW_LINE_LIMIT else entry.raw[:RAW_LINE_LIMIT] + " …"
    return (
        f'<section class="step unreadable" id="line-{entry.line}"><div class="body">'
        f"<h2>Line {entry.line}: unreadable, {escape(entry.reason)}</h2>"
        f"<pre>{escape(raw)}</pre></div></section>"
    )


def _gap_html(after: int, before: int) -> str:
    missing = f"step {after + 1}" if before == after + 2 else f"steps {after + 1}–{before - 1}"
    return f'<p class="gap problem">{missing} missing from the transcript</p>'


STYLE = """
body{font:14px/1.45 system-ui,sans-serif;margin:24px;color:#222;max-width:1400px}
h1{font-size:20px} h2{font-size:15px;margin:0 0 6px} .t{color:#666;font-weight:400}
dl.facts{display:grid;grid-template-columns:max-content 1fr;gap:2px 12px}
dl.facts dt{color:#666} dl.facts dd{margin:0}
.step{display:flex;gap:16px;border-top:1px solid #ddd;padding:12px 0}
.step .body{flex:1;min-width:0} .text{white-space:pre-wrap;margin:6px 0}
.screenshot{max-width:560px;border:1px solid #ccc}
pre{background:#f6f6f6;padding:8px;overflow:auto;font-size:12px;white-space:pre-wrap;margin:4px 0}
.problem{color:#c8322d} .unreadable h2{color:#c8322d} .usage,.url{color:#555;margin:2px 0}
"""


def render_transcript_page(
    *,
    title: str,
    facts: list[tuple[str, str]],
    task_folder: Path,
    page_folder: Path,
    back_href: str,
) -> str:
    """The task's facts, its prompt, then every step of its transcript in order (the prompt
    is the harness's, in the task folder; the transcript and its screenshots the agent's)."""
    prompt_path = task_folder / PROMPT
    files = agent_files(task_folder)
    prompt = (
        prompt_path.read_text(encoding="utf-8", errors="replace") if prompt_path.is_file() else None
    )
    try:
        entries = read_transcript(files / TRANSCRIPT)
        unreadable_file = ""
    except OSError as exc:
        entries, unreadable_file = [], f"cannot read {TRANSCRIPT}: {exc.strerror or exc}"
    parts = [
        '<!doctype html>\n<html lang="en"><head><meta charset="utf-8">'
        f"<title>{escape(title)}</title><style>{STYLE}</style></head><body>",
        f'<p><a class="back" href="{back_href}">← report</a></p><h1>{escape(title)}</h1>',
        '<dl class="facts">'
        + "".join(f"<dt>{escape(k)}</dt><dd>{escape(v)}</dd>" for k, v in facts)
        + "</dl>",
    ]
    if prompt is not None:
        parts.append(f"<details><summary>prompt</summary><pre>{escape(prompt)}</pre></details>")
    steps = [e for e in entries if isinstance(e, Step)]
    parts.append(
        f'<p class="summary">{len(steps)} steps'
        + _unreadable_count(len(entries) - len(steps))
        + "</p>"
    )
    if not entries:
        parts.append(
            f'<p class="problem">{escape(unreadable_file or "The transcript is empty.")}</p>'
        )
    previous: int | None = None
    for entry in entries:
        if isinstance(entry, Unreadable):
            parts.append(_unreadable_html(entry))
            continue
        if previous is not None and entry.number is not None and entry.number > previous + 1:
            parts.append(_gap_html(previous, entry.number))
        previous = entry.number if entry.number is not None else previous
        parts.append(_step_html(entry, files, page_folder))
    parts.append("</body></html>\n")
    return "\n".join(parts)


def _unreadable_count(count: int) -> str:
    return "" if not count else f", {count} unreadable line{'s' if count > 1 else ''}"


def has_transcript(task_folder: Path | None) -> bool:
    return task_folder is not None and (agent_files(task_folder) / TRANSCRIPT).is_file()
