"""The HTML report's sections on what produced a result set and how sure its figures are:
the manifest (first thing on the page), the figures with their 95 % intervals, pass@k and
pass^k, the breakdowns by environment and category, the errors with their causes, and — for
several sets — whether their differences are larger than the noise."""

from __future__ import annotations

import json
from html import escape
from typing import Any

from apps.bench.grading import (
    ResultSet,
    TableCells,
    category_table,
    difference_table,
    environment_table,
    interval_table,
    outcome_counts,
    pass_k_line,
    report_correctness,
)

SECTION_STYLE = """
.manifest{background:#f4f7fb;border:1px solid #d5dfeb;padding:8px 14px;margin:8px 0 16px}
.manifest th{color:#444;font-weight:600;vertical-align:top;padding-right:14px}
.manifest td{font-family:ui-monospace,monospace;font-size:12px}
.passk{font-size:15px;font-weight:600} .beyond{color:#1f6fb4;font-weight:600}
.errors li{color:#8a1f1b}
"""


def table(table_id: str, cells: TableCells) -> str:
    header, lines = cells
    head = "".join(f"<th>{escape(h)}</th>" for h in header)
    body = "".join(
        "<tr>" + "".join(f"<td>{escape(c)}</td>" for c in line) + "</tr>" for line in lines
    )
    return f'<table id="{table_id}"><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>'


def _produced_by(config: dict[str, Any]) -> str:
    if config.get("control_agent"):
        return f"control agent {config['control_agent']}"
    agent = config.get("agent")
    if isinstance(agent, dict):
        return f"reference agent {agent.get('kind')} on {agent.get('model')}"
    command = config.get("agent_subprocess")
    return " ".join(command) if isinstance(command, list) else str(command or "?")


def manifest_section(rs: ResultSet) -> str:
    """What produced the set (manifest.json), with the counts by outcome of what is graded."""
    counts = outcome_counts(rs.rows, rs.errors)
    tally = f"{counts['passed']} passed, {counts['failed']} failed, {counts['error']} errors"
    m = rs.manifest
    if m is None:
        return (
            f'<div class="manifest" id="manifest-{escape(rs.name)}"><p>Result set '
            f"<b>{escape(rs.name)}</b>: no manifest.json (a result set older than manifests, "
            f"or not written by bench run); outcomes: {escape(tally)}</p></div>"
        )
    config = m.get("config") or {}
    host = m.get("machine") or {}
    catalogs = ", ".join(h[:12] for h in m.get("catalog_hashes") or []) or "unknown"
    facts = [
        ("result set", rs.name),
        ("produced by", _produced_by(config)),
        ("version, commit", f"{m.get('version')}, {m.get('commit')}"),
        ("started – finished", f"{m.get('started_at')} – {m.get('finished_at')}"),
        (
            "speed factor, trials",
            f"{config.get('speed_factor')}, {config.get('trials', 1)} "
            f"({len(m.get('runs') or [])} bench run(s))",
        ),
        ("outcomes", tally),
        (
            "scenarios, catalog",
            f"{len(m.get('scenarios') or {})} scenario hashes; catalog {catalogs}",
        ),
        (
            "machine",
            f"{host.get('host')} · {host.get('platform')} · Python {host.get('python')} · "
            f"{host.get('cpus')} CPUs · load {host.get('load_average')}",
        ),
    ]
    rows = "".join(f"<tr><th>{escape(k)}</th><td>{escape(str(v))}</td></tr>" for k, v in facts)
    used = escape(json.dumps(config, indent=1, sort_keys=True, default=str))
    return (
        f'<div class="manifest" id="manifest-{escape(rs.name)}"><table>{rows}</table>'
        f"<details><summary>config as used</summary><pre>{used}</pre></details></div>"
    )


def uncertainty_section(rs: ResultSet, window: float) -> str:
    if not rs.rows:
        return ""
    passk = pass_k_line(rs.rows)
    return (
        "<h2>Figures with 95 % intervals</h2>"
        '<p class="note">Wilson score interval for rates, percentile bootstrap (2000 resamples) '
        "for medians; errors are not attempts.</p>"
        f"{table('intervals', interval_table(rs.rows, window))}"
        + (f'<p class="passk" id="passk">{escape(passk)}</p>' if passk else "")
        + "<h2>By environment</h2>"
        f"{table('environments', environment_table(rs.rows, window))}"
        "<h2>By category</h2>"
        f"{table('categories', category_table(rs.rows, window))}"
    )


def reports_section(rs: ResultSet) -> str:
    """Each judged report of the set: what the agent said, and whether it says what it must."""
    found = report_correctness(rs.rows)
    if found is None:
        return ""
    rows = "".join(
        f'<tr class="{"ok" if r.judgement.correct else "fail"}">'
        f"<td>{escape(r.environment)}/{escape(r.label)}</td>"
        f"<td>{'passed' if r.success else 'failed'}</td>"
        f"<td>{'correct' if r.judgement.correct else 'incorrect'}</td>"
        f"<td>{escape(str(r.result.get('contact_message') or ''))}</td>"
        f"<td>{escape(r.judgement.why)}</td></tr>"
        for r in rs.rows
        if r.judgement is not None
    )
    head = "".join(f"<th>{h}</th>" for h in ("task", "outcome", "report", "message", "why"))
    return (
        f"<h2>Reports of {escape(rs.name)} (judged by {escape(found.by)})</h2>"
        f"<p>Reports judged correct: {found.judged}. Success with a correct report (tasks with "
        f"a contact rubric): {found.success_with_report}.</p>"
        f'<table class="reports"><thead><tr>{head}</tr></thead><tbody>{rows}</tbody></table>'
    )


def errors_section(rs: ResultSet) -> str:
    if not rs.errors:
        return ""
    items = "".join(
        f"<li>{escape(e.environment)}/{escape(str(e))}: {escape(e.cause or 'no cause recorded')}</li>"
        for e in rs.errors
    )
    return (
        f"<h2>Errors of {escape(rs.name)}: {len(rs.errors)} (not graded, not in any rate)</h2>"
        f'<ul class="errors">{items}</ul>'
    )


def differences_section(sets: list[ResultSet], window: float) -> str:
    header, lines = difference_table(sets, window)
    body = "".join(
        "<tr>"
        + "".join(f"<td>{escape(c)}</td>" for c in line[:-1])
        + f'<td class="{"beyond" if line[-1] == "beyond the noise" else ""}">{escape(line[-1])}</td>'
        + "</tr>"
        for line in lines
    )
    head = "".join(f"<th>{escape(h)}</th>" for h in header)
    return (
        "<h2>Differences beyond the noise</h2>"
        '<p class="note">The first set minus each other; a difference counts when its 95 % '
        "interval leaves out 0 (Newcombe's interval for rates, bootstrap for medians).</p>"
        f'<table id="differences"><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>'
    )
