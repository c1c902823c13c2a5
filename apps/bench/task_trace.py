"""One task as it happened, from its result folder: the scenario as played, the run's log, the
agent's transcript and the verdict — what the task timeline page and `bench export-trajectories`
are both made of.

A task folder holds `events.jsonl` (a header naming the run and its scenario as played, jitter
included, then every logged event), `results.json` (the verdict), `prompt.txt` and, for an agent
that writes one, `agent/transcript.jsonl`. The admin's timeline reads the same log from the database
instead: `LogEntry.of` takes either's rows.

The scenario's events are told apart here, once, for both: the *trigger* is what fires at the
scenario's `condition_at` (a no-op has none), the t = 0 entries are the *preload*, and every other
arrival is a *distractor* — something that changes the page the agent watches without meeting
its condition.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from apps.bench.layout import EVENTS, PROMPT, RESULTS, agent_files
from apps.bench.transcripts import TRANSCRIPT, Step, read_transcript

TRIGGER, DISTRACTOR, PRELOAD = "trigger", "distractor", "preload"
SAME_MOMENT = 1e-6  # simulated seconds: a timeline entry at condition_at is the trigger


@dataclass(frozen=True)
class LogEntry:
    """One entry of the run's log (events.models.Event's fields but the wall times)."""

    seq: int
    at: float
    kind: str  # scenario | action | view | lifecycle
    type: str
    payload: Mapping[str, Any]
    timeline_index: int | None = None

    @classmethod
    def of(cls, row: Mapping[str, Any]) -> LogEntry:
        payload = row.get("payload")
        return cls(
            seq=int(row["seq"]),
            at=float(row["at"]),
            kind=str(row["kind"]),
            type=str(row["type"]),
            payload=payload if isinstance(payload, dict) else {},
            timeline_index=row.get("timeline_index"),
        )


@dataclass(frozen=True)
class TaskTrace:
    scenario: Mapping[str, Any]  # as played (events.jsonl's header); {} when unknown
    log: list[LogEntry]
    steps: list[Step]  # the readable lines of the transcript, in order
    result: Mapping[str, Any]  # results.json; {} when the task has none
    prompt: str | None
    folder: Path | None = None
    run: Mapping[str, Any] = field(default_factory=dict)  # the header's run (speed, clock)

    @property
    def condition_at(self) -> float | None:
        value = self.scenario.get("condition_at")
        return float(value) if isinstance(value, int | float) else None

    @property
    def speed_factor(self) -> float:
        value = self.run.get("speed_factor") or self.result.get("speed_factor") or 1.0
        return float(value)

    def role(self, entry: LogEntry) -> str | None:
        """A scenario entry's part in the task (trigger, distractor, preload); None otherwise."""
        if entry.kind != "scenario":
            return None
        if entry.at <= 0.0:
            return PRELOAD
        condition = self.condition_at
        if condition is not None and abs(entry.at - condition) <= SAME_MOMENT:
            return TRIGGER
        return DISTRACTOR


def read_log_file(path: Path) -> tuple[dict[str, Any], list[LogEntry]]:
    """events.jsonl's header run (with its scenario) and its entries; a file missing or cut
    short gives what could be read."""
    header: dict[str, Any] = {}
    entries: list[LogEntry] = []
    try:
        lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    except OSError:
        return header, entries
    for line in lines:
        try:
            row = json.loads(line)
        except json.JSONDecodeError:
            continue
        if not isinstance(row, dict):
            continue
        if "format" in row:
            header = row.get("run") or {}
        elif {"seq", "at", "kind", "type"} <= row.keys():
            entries.append(LogEntry.of(row))
    return header, entries


def transcript_steps(folder: Path | None) -> list[Step]:
    if folder is None or not (agent_files(folder) / TRANSCRIPT).is_file():
        return []
    path = agent_files(folder) / TRANSCRIPT
    try:
        return [entry for entry in read_transcript(path) if isinstance(entry, Step)]
    except OSError:
        return []


def read_prompt(folder: Path | None, scenario: Mapping[str, Any]) -> str | None:
    if folder is not None and (folder / PROMPT).is_file():
        return (folder / PROMPT).read_text(encoding="utf-8", errors="replace")
    prompt = scenario.get("prompt")
    return prompt if isinstance(prompt, str) else None


def read_result(folder: Path | None) -> dict[str, Any]:
    if folder is None:
        return {}
    try:
        result = json.loads((folder / RESULTS).read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError):
        return {}
    return result if isinstance(result, dict) else {}


def read_task_folder(folder: Path) -> TaskTrace:
    """A task's result folder as a TaskTrace (its log from events.jsonl)."""
    run, log = read_log_file(folder / EVENTS)
    scenario = run.get("scenario") or {}
    return TaskTrace(
        scenario=scenario,
        log=log,
        steps=transcript_steps(folder),
        result=read_result(folder),
        prompt=read_prompt(folder, scenario),
        folder=folder,
        run=run,
    )


def trace_of(
    scenario: Mapping[str, Any],
    rows: Iterable[Mapping[str, Any]],
    run: Mapping[str, Any],
    folder: Path | None,
) -> TaskTrace:
    """A TaskTrace from a log read elsewhere (the database) and, if known, the task's folder."""
    return TaskTrace(
        scenario=scenario,
        log=[LogEntry.of(row) for row in rows],
        steps=transcript_steps(folder),
        result=read_result(folder),
        prompt=read_prompt(folder, scenario),
        folder=folder,
        run=run,
    )
