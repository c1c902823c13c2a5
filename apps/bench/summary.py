"""`results/<NAME>/summary.json`: one result set in one file a notebook loads with `json` or
`pandas` (`pd.json_normalize(summary["tasks"])`).

Written by `bench run` (after its manifest) and again by `bench grade` of the whole set: what
produced it (config, versions, scenario and catalog hashes, from the manifest), every graded
task's verdict and figures, the errors apart, and the aggregates `bench grade` prints. Its
JSON Schema is `summary.schema.json` beside this module (`SCHEMA_PATH`); the format's name and
version are in `format`, changed whenever a field changes meaning.
"""

from __future__ import annotations

import json
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from apps.bench.config import BenchConfig
from apps.bench.grading import (
    GROUPS,
    TIMELY_GROUPS,
    Rate,
    ResultSet,
    Row,
    load_result_sets,
    mean,
    median,
    outcome_counts,
    pass_k,
    summarise,
    trials_of,
)
from apps.bench.manifest import machine
from apps.bench.runner import write_json_atomically

SUMMARY = "summary.json"
FORMAT = "sentinel-summary/1"
SCHEMA_PATH = Path(__file__).with_name("summary.schema.json")


def _rate(rate: Rate) -> dict[str, Any]:
    return {"passed": rate.passed, "total": rate.total, "rate": rate.fraction}


def _task(row: Row, window: float, hashes: dict[str, str]) -> dict[str, Any]:
    result = row.result
    return {
        "scenario_id": row.name,
        "environment": row.environment,
        "category": row.category,
        "trial": row.trial,
        "outcome": "passed" if row.success else "failed",
        "success": row.success,
        "timely": row.timely(window),
        "detail": result.get("detail"),
        "reaction_time": row.reaction_time,
        "condition_at": row.condition_at,
        "evaluation_time": row.evaluation_time,
        "contact_message": result.get("contact_message"),
        "clock": result.get("clock"),
        "speed_factor": result.get("speed_factor"),
        "run": row.run,
        "views": row.views,
        "actions": row.actions,
        "prompt_tokens": row.prompt_tokens,
        "completion_tokens": row.completion_tokens,
        "tool_calls": row.tool_calls,
        "cost_usd": row.cost_usd,
        "scenario_hash": hashes.get(row.name),
    }


def _aggregates(result_set: ResultSet, window: float) -> dict[str, Any]:
    rows = result_set.rows
    summary = summarise(rows, window)
    k = pass_k(rows)
    return {
        **outcome_counts(rows, result_set.errors),
        "graded": summary.total,
        "trials": trials_of(rows),
        "success": {group: _rate(summary.rates[group]) for group in GROUPS},
        "timely_success": {group: _rate(summary.timely[group]) for group in TIMELY_GROUPS},
        "reaction_time_median": median(summary.reaction),
        "reaction_time_mean": mean(summary.reaction),
        "cost_usd_total": sum(summary.costs) if summary.costs else None,
        "cost_usd_median": median(summary.costs),
        "tokens_median": median(summary.total_tokens),
        "tool_calls_median": median(summary.tool_calls),
        "unpriced": summary.unpriced,
        "pass_at_k": None if k.k < 2 else {"k": k.k, "pass_at_k": k.at_k, "pass_hat_k": k.all_k},
    }


def build_summary(
    result_set: ResultSet, window: float, *, now: datetime | None = None
) -> dict[str, Any]:
    """The summary of one whole result set (pure but for `now`, default the wall clock)."""
    manifest = result_set.manifest or {}
    hashes = dict(manifest.get("scenarios") or {})
    return {
        "format": FORMAT,
        "name": result_set.name,
        "written_at": (now or datetime.now(UTC)).isoformat(timespec="seconds"),
        "reaction_window": window,
        "config": manifest.get("config") or {},
        "versions": {
            "sentinel": manifest.get("version") or "unknown",
            "commit": manifest.get("commit") or "unknown",
            "python": (manifest.get("machine") or machine())["python"],
        },
        "scenarios": hashes,
        "catalog_hashes": manifest.get("catalog_hashes") or [],
        "aggregates": _aggregates(result_set, window),
        "tasks": [_task(row, window, hashes) for row in result_set.rows],
        "errors": [
            {
                "scenario_id": e.name,
                "environment": e.environment,
                "trial": e.trial,
                "cause": e.cause,
            }
            for e in result_set.errors
        ],
    }


def write_summary(run_dir: Path, summary: dict[str, Any]) -> Path:
    write_json_atomically(run_dir / SUMMARY, summary)
    return run_dir / SUMMARY


def write_set_summary(results_dir: Path, name: str, config: BenchConfig, window: float) -> Path:
    """Read the whole result set `results_dir/name` and write its summary.json there."""
    (result_set,) = load_result_sets(results_dir, [name], config)
    return write_summary(results_dir / name, build_summary(result_set, window))


def schema() -> dict[str, Any]:
    return json.loads(SCHEMA_PATH.read_text(encoding="utf-8"))
