"""A run as JSON Lines: one header line (the run and its recorded verdict), then one per event.

`export_lines(run)` and `import_lines(lines)` are inverses: an imported run has the same log
(seq, at, kind, type, payload, timeline index, wall times) under a new id and token, is closed
(so no ticker or agent can touch it), and carries the exported verdict as its recorded one.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Any

from django.conf import settings
from django.db import transaction
from django.utils import timezone

from apps.kit.log_payloads import logged_schema, logged_types
from apps.replay.models import RunVerdict
from apps.replay.records import latest_verdict, record_verdict
from apps.scenarios.format import ScenarioError, parse_scenario
from events.catalog import load_catalog
from events.models import EVENT_FIELDS, ClockMode, Event, EventKind, Run, RunStatus
from events.registry import EMPTY, Environment, LoggedEvent, get_environment
from events.schemas import PayloadError, validate_payload
from events.timing import SpeedFactorError, validate_speed_factor

FORMAT = "sentinel-run/1"


class TransferError(ValueError):
    """A run file cannot be imported; the message names the line and the field."""


def export_records(run: Run) -> Iterator[dict[str, Any]]:
    """The header, then every event row, as JSON values (the control API answers them as one
    list; `export_lines` writes one per line)."""
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
    yield header
    yield from Event.objects.filter(run_id=run.pk).order_by("seq").values(*EVENT_FIELDS)


def export_lines(run: Run) -> Iterator[str]:
    for record in export_records(run):
        yield json.dumps(record, ensure_ascii=False)


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


def _scenario(spec: Any, number: int) -> dict[str, Any]:
    """The run's scenario, checked as /init and scenario files are (its environment, its
    timeline against the event types' schemas, every text storable)."""
    try:
        parse_scenario(spec, source=f"line {number}: run.scenario")
    except ScenarioError as error:
        raise TransferError(str(error)) from None
    return spec


def _finite(meta: dict, key: str, number: int, default: float | None) -> float | None:
    value = meta.get(key, default)
    if value is None and default is None:
        return None
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise TransferError(f"line {number}: field '{key}' must be a finite number, got {value!r}")
    return float(value)


def _catalog(meta: dict, catalog_dir, warnings: list[str]):
    """The catalog to replay with: the one the operator named (--catalog), else the file's own
    when this server already plays it (the configured folder, or one a run here was created
    on), else the configured one. An imported file never points the server at another folder
    on the disk."""
    if catalog_dir is not None:
        return load_catalog(catalog_dir)
    named = str(meta.get("catalog_dir") or "")
    configured = str(Path(settings.SENTINEL_CATALOG_DIR).resolve())
    if named and (named == configured or Run.objects.filter(catalog_dir=named).exists()):
        return load_catalog(named)
    if named:
        warnings.append(
            f"the file names catalog {named!r}, which this server does not play; using "
            f"{configured} (pass --catalog to choose another)"
        )
    return load_catalog(None)


def _event(data: dict, number: int, environment: Environment) -> dict[str, Any]:
    values = {}
    for key in EVENT_FIELDS:
        if key in ("timeline_index", "lateness_ms"):
            values[key] = data.get(key)
        else:
            values[key] = _need(
                data, key, number, "every event line has " + ", ".join(EVENT_FIELDS[:6])
            )
    kind, kind_of = values["kind"], values["type"]
    if kind not in EventKind.values:
        raise TransferError(
            f"line {number}: field 'kind' is {kind!r}; allowed: {', '.join(EventKind.values)}"
        )
    if not isinstance(kind_of, str) or not 0 < len(kind_of) <= 64:
        raise TransferError(f"line {number}: field 'type' must be a name of 1–64 characters")
    schema = logged_schema(environment, kind, kind_of)
    if schema is None:
        raise TransferError(
            f"line {number}: {kind} type {kind_of!r} is not one a {environment.name} run logs; "
            f"allowed: {', '.join(logged_types(environment, kind))}"
        )
    if not isinstance(values["payload"], dict):
        raise TransferError(f"line {number}: field 'payload' must be an object")
    for key in ("at", "recorded_at"):
        _finite(values, key, number, None)
    # The schema its door holds such an entry to (an action's, a scenario event type's, the
    # engine's own for lifecycle entries and views): a payload a reducer cannot read would
    # otherwise be imported, and crash every replay of the run.
    try:
        validate_payload(schema, values["payload"], what=f"line {number}: {kind} {kind_of!r}")
    except PayloadError as error:
        raise TransferError(str(error)) from None
    return values


class Replaying:
    """The run's state, folded as the file is read, as a replay will fold it: the file is
    refused at the first event this server cannot apply (a field an action's `decide` derives,
    missing; the schemas cannot know those)."""

    def __init__(self, environment: Environment, catalog) -> None:
        self.environment = environment
        self.state = environment.initial_state(catalog)
        self.baselines: Any = EMPTY

    def apply(self, values: dict[str, Any], number: int) -> None:
        event = LoggedEvent(
            values["seq"], values["at"], values["kind"], values["type"], values["payload"]
        )
        try:
            self.state, self.baselines = self.environment.fold(self.state, (event,), self.baselines)
        except Exception as error:  # a reducer trusts the log; a file can say anything
            if isinstance(error, KeyError):
                why = f"its payload has no field {error.args[0]!r}"
            else:
                why = f"{type(error).__name__}: {error}"
            found = f"line {number}: {event.kind} {event.type!r} cannot be replayed: {why}"
            raise TransferError(" ".join(found.split())) from None  # one line


BATCH = 1_000  # events written at a time: a file of any length is read as a stream


def import_lines(lines: Iterable[str], *, catalog_dir=None) -> tuple[Run, list[str]]:
    """Create a new closed Run with the file's events; returns it and any warnings.

    Everything is checked as it would be on its way in through the API (the scenario, the
    speed factor, the clock, every event's kind, type and payload, by the schema its door
    holds it to), every event is applied as a replay will apply it, and nothing is written
    unless all of it is: a bad file is one error naming its line, and changes nothing."""
    numbered = ((n, line) for n, line in enumerate(lines, 1) if line.strip())
    first = next(numbered, None)
    if first is None:
        raise TransferError("line 1: the file is empty; expected a run header")
    number, line = first
    header = _json(line, number)
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
    if not isinstance(meta, dict):
        raise TransferError(f"line {number}: field 'run' must be an object")
    spec = _scenario(_need(meta, "scenario", number, "the scenario as played"), number)
    environment = get_environment(spec["environment"])
    if meta.get("environment", spec["environment"]) != spec["environment"]:
        raise TransferError(
            f"line {number}: field 'environment' is {meta.get('environment')!r}, but the "
            f"scenario plays {spec['environment']!r}"
        )
    clock_mode = meta.get("clock_mode", ClockMode.LIVE)
    if clock_mode not in ClockMode.values:
        raise TransferError(
            f"line {number}: field 'clock_mode' is {clock_mode!r}; allowed: {', '.join(ClockMode.values)}"
        )
    status = meta.get("status", RunStatus.COMPLETED)
    if status not in RunStatus.values:
        raise TransferError(
            f"line {number}: field 'status' is {status!r}; allowed: {', '.join(RunStatus.values)}"
        )
    try:
        speed_factor = validate_speed_factor(meta.get("speed_factor", 1.0))
    except SpeedFactorError as error:
        raise TransferError(f"line {number}: {error}") from None
    warnings: list[str] = []
    catalog = _catalog(meta, catalog_dir, warnings)
    if catalog.content_hash != meta.get("catalog_hash"):
        warnings.append(
            f"catalog {catalog.directory} has hash {catalog.content_hash[:12]}…, the run used "
            f"{str(meta.get('catalog_hash'))[:12]}…: replay will likely not match"
        )
    with transaction.atomic():
        run = Run.objects.create(
            scenario_id=spec["id"],
            environment=spec["environment"],
            scenario=spec,
            speed_factor=speed_factor,
            clock_mode=clock_mode,
            status=status,
            started_at=_finite(meta, "started_at", number, None),
            sim_time=_finite(meta, "sim_time", number, 0.0),
            skipped=_finite(meta, "skipped", number, 0.0),
            catalog_dir=str(catalog.directory),
            catalog_hash=meta.get("catalog_hash") or catalog.content_hash,
            closed_at=timezone.now(),
        )
        batch: list[Event] = []
        expected = 1
        replaying = Replaying(environment, catalog)
        for number, line in numbered:
            values = _event(_json(line, number), number, environment)
            if values["seq"] != expected:
                raise TransferError(
                    f"line {number}: seq is {values['seq']!r}, expected {expected}: events run "
                    "1, 2, 3 … without gaps or repeats"
                )
            expected += 1
            replaying.apply(values, number)
            batch.append(Event(run=run, **values))
            if len(batch) >= BATCH:
                Event.objects.bulk_create(batch)
                batch = []
        Event.objects.bulk_create(batch)
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
