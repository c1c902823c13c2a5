"""A run as JSON Lines: one header line (the run and its recorded verdict), then one per event.

`export_lines(run)` and `import_lines(lines)` are inverses: an imported run has the same log
(seq, at, kind, type, payload, timeline index, wall times) under a new id and token, is closed
(so no ticker or agent can touch it), and carries the exported verdict as its recorded one.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Iterator
from typing import Any

from django.db import transaction
from django.utils import timezone

from apps.replay.models import RunVerdict
from apps.replay.records import latest_verdict, record_verdict
from events.catalog import CatalogError, load_catalog
from events.models import EVENT_FIELDS, ClockMode, Event, Run, RunStatus

FORMAT = "sentinel-run/1"


class TransferError(ValueError):
    """A run file cannot be imported; the message names the line and the field."""


def export_lines(run: Run) -> Iterator[str]:
    verdict = latest_verdict(run) or record_verdict(run, source="export")
    header = {
        "format": FORMAT,
        "run": {
            "id": run.pk,
            "scenario_id": run.scenario_id,
            "environment": run.environment,
            "scenario": run.spec,
            "speed_factor": run.speed_factor,
            "clock_mode": run.clock_mode,
            "status": run.status,
            "started_at": run.started_at,
            "sim_time": run.sim_time,
            "skipped": run.skipped,
            "catalog_dir": run.catalog_dir,
            "catalog_hash": run.catalog_hash,
            "created_at": run.created_at.isoformat(),
        },
        "verdict": verdict.as_dict(),
    }
    yield json.dumps(header, ensure_ascii=False)
    for row in Event.objects.filter(run_id=run.pk).order_by("seq").values(*EVENT_FIELDS):
        yield json.dumps(row, ensure_ascii=False)


def _json(line: str, number: int) -> dict[str, Any]:
    try:
        value = json.loads(line)
    except json.JSONDecodeError as error:
        raise TransferError(
            f"line {number}: invalid JSON at column {error.colno}: {error.msg}"
        ) from None
    if not isinstance(value, dict):
        raise TransferError(f"line {number}: expected a JSON object, got {type(value).__name__}")
    return value


def _need(data: dict, key: str, number: int, what: str) -> Any:
    if key not in data:
        raise TransferError(f"line {number}: field '{key}' is required ({what})")
    return data[key]


def import_lines(lines: Iterable[str], *, catalog_dir=None) -> tuple[Run, list[str]]:
    """Create a new closed Run with the file's events; returns it and any warnings."""
    numbered = [(n, line) for n, line in enumerate(lines, 1) if line.strip()]
    if not numbered:
        raise TransferError("line 1: the file is empty; expected a run header")
    number, first = numbered[0]
    header = _json(first, number)
    if "format" not in header and "seq" in header:
        # A bare log: bench run saved one before its events.jsonl carried the run's header.
        raise TransferError(
            f"line {number}: an event, not a run header: this log has no scenario or verdict "
            f"to import (a harness events.jsonl from before it was written as {FORMAT!r}); "
            "export the run with export_run, or run the task again"
        )
    if header.get("format") != FORMAT:
        raise TransferError(
            f"line {number}: field 'format' must be {FORMAT!r}, got {header.get('format')!r}"
        )
    meta = _need(header, "run", number, "the exported run")
    spec = _need(meta, "scenario", number, "the scenario as played")
    clock_mode = meta.get("clock_mode", ClockMode.LIVE)
    if clock_mode not in ClockMode.values:
        raise TransferError(
            f"line {number}: field 'clock_mode' is {clock_mode!r}; allowed: {', '.join(ClockMode.values)}"
        )
    warnings = []
    try:
        catalog = load_catalog(catalog_dir or meta.get("catalog_dir"))
    except CatalogError:
        catalog = load_catalog(catalog_dir)
    if catalog.content_hash != meta.get("catalog_hash"):
        warnings.append(
            f"catalog {catalog.directory} has hash {catalog.content_hash[:12]}…, the run used "
            f"{str(meta.get('catalog_hash'))[:12]}…: replay will likely not match"
        )
    events = []
    for number, line in numbered[1:]:
        data = _json(line, number)
        values = {}
        for key in EVENT_FIELDS:
            if key in ("timeline_index", "lateness_ms"):
                values[key] = data.get(key)
            else:
                values[key] = _need(
                    data, key, number, "every event line has " + ", ".join(EVENT_FIELDS[:6])
                )
        events.append(values)
    seqs = [e["seq"] for e in events]
    if seqs != list(range(1, len(seqs) + 1)):
        raise TransferError("events: seq must run 1, 2, 3 … without gaps or repeats")
    with transaction.atomic():
        run = Run.objects.create(
            scenario_id=_need(meta, "scenario_id", 1, "the scenario id"),
            environment=_need(meta, "environment", 1, "the environment"),
            scenario=spec,
            speed_factor=meta.get("speed_factor", 1.0),
            clock_mode=clock_mode,
            status=meta.get("status", RunStatus.COMPLETED),
            started_at=meta.get("started_at"),
            sim_time=meta.get("sim_time", 0.0),
            skipped=meta.get("skipped", 0.0),
            catalog_dir=str(catalog.directory),
            catalog_hash=meta.get("catalog_hash", catalog.content_hash),
            closed_at=timezone.now(),
        )
        Event.objects.bulk_create(Event(run=run, **values) for values in events)
        verdict = header.get("verdict")
        if isinstance(verdict, dict):
            RunVerdict.objects.create(
                run=run,
                source="import",
                **{
                    k: verdict.get(k)
                    for k in (
                        "success",
                        "detail",
                        "graded_at_seq",
                        "event_count",
                        "state_digest",
                        "log_digest",
                    )
                },
            )
    return run, warnings
