"""Mirror a results tree into BenchmarkRun / TaskResult rows."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from django.utils import timezone

from apps.bench.config import BenchConfig
from apps.bench.grading import load_rows, task_errors
from apps.bench.layout import ERROR, trial_folder
from apps.bench.models import BenchmarkRun, TaskResult
from events.models import Run


def record_benchmark(
    name: str,
    run_dir: Path,
    config: BenchConfig,
    *,
    agent: str | None,
    started_at,
    raw_config: dict[str, Any],
) -> BenchmarkRun:
    benchmark, _ = BenchmarkRun.objects.update_or_create(
        name=name,
        defaults={
            "config": {k: v for k, v in raw_config.items() if k != "control_token"},
            "agent": agent or "",
            "speed_factor": config.speed_factor,
            "results_dir": str(run_dir),
        },
    )
    if benchmark.started_at is None:
        benchmark.started_at = started_at
    benchmark.finished_at = timezone.now()
    benchmark.save()
    for row in load_rows(run_dir, config) if run_dir.is_dir() else []:
        # Link the events.Run only when it lives in this database (an embedded server).
        run_id = (
            row.run
            if row.run and Run.objects.filter(pk=row.run, scenario_id=row.name).exists()
            else None
        )
        TaskResult.objects.update_or_create(
            benchmark=benchmark,
            scenario_id=row.name,
            trial=row.trial,
            defaults={
                "environment": row.environment,
                "category": row.category,
                "success": row.success,
                "reaction_time": row.reaction_time,
                "condition_at": row.condition_at,
                "evaluation_time": row.evaluation_time,
                "input_tokens": row.prompt_tokens,
                "output_tokens": row.completion_tokens,
                "tool_calls": row.tool_calls,
                "cost_usd": row.cost_usd,
                "costs": row.costs,
                "result": row.result,
                "run_id": run_id,
                "error": "",
            },
        )
    for error in task_errors(run_dir) if run_dir.is_dir() else []:
        folder = trial_folder(run_dir / error.environment / error.name, error.trial)
        TaskResult.objects.update_or_create(
            benchmark=benchmark,
            scenario_id=error.name,
            trial=error.trial,
            defaults={
                "environment": error.environment,
                "success": None,
                "error": (folder / ERROR).read_text(encoding="utf-8", errors="replace")[:20000],
            },
        )
    return benchmark
