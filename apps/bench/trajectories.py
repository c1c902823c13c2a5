"""`bench export-trajectories`: a result set as training data, one JSON object per task.

Schema `sentinel-trajectory/1` (README, "Trajectories for training"): the task (scenario,
prompt), the agent's steps in order on the run's simulated clock — from its transcript when it
wrote one, else from the run's log (its page views, actions and contact) —, the environment's
events (the scenario's entries as they fired, each with its part: trigger, distractor,
preload), and the verdict as the reward signal. Plain JSON Lines: `json`, `pandas.read_json(…,
lines=True)` and `datasets.load_dataset("json", …)` all load it.

Tasks that ended in an error (error.txt, no results.json) are no result, so no record: the
count left out is reported beside the output.
"""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path
from typing import Any, TextIO

from apps.bench.grading import Row, load_rows, task_errors
from apps.bench.layout import agent_files
from apps.bench.task_trace import LogEntry, TaskTrace, read_task_folder
from apps.bench.transcripts import Step

FORMAT = "sentinel-trajectory/1"
AGENT_LOG_KINDS = ("view", "action")  # what the agent did, as the run logged it
CONTACTS = ("contact_get", "contact_post")


def _transcript_step(step: Step, results_root: Path, folder: Path) -> dict[str, Any]:
    screenshot = step.screenshot if isinstance(step.screenshot, str) and step.screenshot else None
    return {
        "step": step.number,
        "sim_start": step.sim_start,
        "sim_time": step.sim_time,
        "observation": {
            "url": step.url,
            "text": step.observation,
            # relative to the result set's folder, so a trainer given that folder opens it
            "screenshot": (agent_files(folder) / screenshot).relative_to(results_root).as_posix()
            if screenshot
            else None,
        },
        "action": {"tool": step.tool, "arguments": step.arguments, "text": step.text},
        "result": step.result,
        "usage": step.usage,
        "checks": step.checks,
    }


def _log_step(number: int, entry: LogEntry) -> dict[str, Any]:
    path = entry.payload.get("path") if entry.kind == "view" else None
    return {
        "step": number,
        "sim_start": entry.at,
        "sim_time": entry.at,
        "observation": {"url": path, "text": None, "screenshot": None},
        "action": {"tool": entry.type, "arguments": dict(entry.payload), "text": None},
        "result": None,
        "usage": None,
        "checks": None,
    }


def environment_event(trace: TaskTrace, entry: LogEntry) -> dict[str, Any]:
    return {
        "seq": entry.seq,
        "sim_time": entry.at,
        "type": entry.type,
        "payload": entry.payload,
        "role": trace.role(entry),
    }


def agent_log(trace: TaskTrace) -> list[LogEntry]:
    """The agent's own entries of the run's log: page views, actions, contacts."""
    return [
        entry
        for entry in trace.log
        if entry.kind in AGENT_LOG_KINDS or (entry.kind == "lifecycle" and entry.type in CONTACTS)
    ]


def trajectory(
    result_set: str, row: Row, trace: TaskTrace, results_root: Path, window: float
) -> dict[str, Any]:
    """One task's record (schema `sentinel-trajectory/1`)."""
    assert row.folder is not None
    if trace.steps:
        steps = [_transcript_step(s, results_root, row.folder) for s in trace.steps]
        source = "transcript"
    else:
        steps = [_log_step(n, entry) for n, entry in enumerate(agent_log(trace), start=1)]
        source = "log"
    scenario = trace.scenario
    result = trace.result
    reaction = row.reaction_time
    return {
        "format": FORMAT,
        "result_set": result_set,
        "task": row.name,
        "trial": row.trial,
        "environment": row.environment,
        "category": row.category,
        "scenario": {
            "id": scenario.get("id", row.name),
            "condition_at": trace.condition_at,
            "kill_at": scenario.get("kill_at"),
            "event_timeline_end": scenario.get("event_timeline_end"),
            "speed_factor": trace.speed_factor,
            "clock": result.get("clock"),
            "timeline_shift": result.get("timeline_shift"),
        },
        "prompt": trace.prompt,
        "steps_from": source,
        "steps": steps,
        "events": [environment_event(trace, e) for e in trace.log if e.kind == "scenario"],
        "reward": {
            "success": row.success,
            "timely": row.timely(window),
            "reaction_time": reaction,
            "reaction_time_sim": None if reaction is None else reaction * trace.speed_factor,
            "detail": result.get("detail"),
            "contact_message": result.get("contact_message"),
        },
    }


def trajectories(
    run_dir: Path, result_set: str, rows: list[Row], window: float
) -> Iterator[dict[str, Any]]:
    for row in rows:
        if row.folder is not None:
            yield trajectory(result_set, row, read_task_folder(row.folder), run_dir, window)


def export_trajectories(run_dir: Path, out: TextIO, window: float) -> tuple[int, int]:
    """Write one line per task of the result set at `run_dir`; (records, errors left out)."""
    rows = load_rows(run_dir)
    written = 0
    for record in trajectories(run_dir, run_dir.name, rows, window):
        out.write(json.dumps(record, ensure_ascii=False, default=str) + "\n")
        written += 1
    return written, len(task_errors(run_dir))
