"""Scenario files ⇄ Scenario rows, byte for byte.

`read_scenario_file` validates a file with the format module and captures its values *and* its
shape; `scenario_document` rebuilds the JSON object from a row; `scenario_text` renders it the
way our files are written (`json.dump(indent=2)` plus a newline). An unedited row renders to
exactly the bytes it was read from.
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from django.db import transaction

from apps.scenarios.format import (
    DEV_FILENAME,
    parse_dev_scenario,
    parse_scenario,
    read_json_file,
)
from apps.scenarios.format import (
    Scenario as ParsedScenario,
)
from apps.scenarios.models import (
    DEFAULT_KEY_ORDER,
    DEV_KEY_ORDER,
    EVENT_KEY_ORDER,
    Scenario,
    TimelineEvent,
)

NUMBER_KEYS = ("condition_at", "event_timeline_end", "kill_at", "duration")
KNOWN_KEYS = frozenset(DEFAULT_KEY_ORDER) | {"duration"}


def render_json(document: Any) -> str:
    return json.dumps(document, indent=2) + "\n"


def sha256(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


@dataclass
class ScenarioFile:
    """A validated file: the row to save and its timeline, not yet in the database."""

    row: Scenario
    events: list[TimelineEvent] = field(default_factory=list)
    text: str = ""


def _is_int(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def read_scenario_file(path: Path, root: Path) -> ScenarioFile:
    """Validate `path` (raises ScenarioError, one line naming file and field) and capture it."""
    text, data = read_json_file(path)
    return scenario_file_of(data, text, path.relative_to(root).as_posix(), source=str(path))


def scenario_file_of(data: Any, text: str, relative_path: str, *, source: str) -> ScenarioFile:
    """Validate a scenario document (raises ScenarioError) and capture it as an unsaved row,
    as `read_scenario_file` does for a file (the generator proves documents not yet written)."""
    is_dev = relative_path.rsplit("/", 1)[-1] == DEV_FILENAME
    parsed = (parse_dev_scenario if is_dev else parse_scenario)(data, source=source)
    row = Scenario(
        path=relative_path,
        scenario_id=parsed.id,
        environment=parsed.environment,
        prompt=data.get("prompt", ""),
        start_page=data.get("start_page", ""),
        watch_page=data.get("watch_page", ""),
        condition_at=parsed.condition_at,
        event_timeline_end=parsed.event_timeline_end,
        kill_at=parsed.kill_at,
        eval_sql=data.get("eval_sql", ""),
        taxonomy=data.get("taxonomy", {}),
        annotator_notes=data.get("annotator_notes", ""),
        solution=data.get("solution", []),
        is_dev=is_dev,
        key_order=list(data),
        int_keys=[k for k in NUMBER_KEYS if _is_int(data.get(k))],
        extra={k: v for k, v in data.items() if k not in KNOWN_KEYS},
    )
    events = []
    for position, raw in enumerate(data["events"]):
        events.append(
            TimelineEvent(
                position=position,
                # The authored time, not the parsed one (dev.json times are read as 0.0).
                time=float(raw["time"]),
                type=raw["type"],
                payload=raw.get("payload", {}),
                time_is_int=_is_int(raw["time"]),
                key_order=[] if list(raw) == list(EVENT_KEY_ORDER) else list(raw),
                extra={k: v for k, v in raw.items() if k not in EVENT_KEY_ORDER},
            )
        )
    return ScenarioFile(row=row, events=events, text=text)


def _number(row: Scenario, key: str, value: float | None) -> float | int | None:
    if value is None:
        return None
    if key in (row.int_keys or []) and math.isfinite(value) and value == int(value):
        return int(value)
    return value


def timeline_of(row: Scenario) -> list[TimelineEvent]:
    """The row's timeline in file order; uses a `prefetch_related("timeline")` when there is one."""
    return sorted(row.timeline.all(), key=lambda event: (event.position, event.pk))


def scenario_document(row: Scenario, events: list[TimelineEvent] | None = None) -> dict[str, Any]:
    """The scenario as a JSON object, keys in the order of the file it came from."""
    if events is None:
        events = timeline_of(row)
    values: dict[str, Any] = {
        "id": row.scenario_id,
        "environment": row.environment,
        "start_page": row.start_page,
        "watch_page": row.watch_page,
        "prompt": row.prompt,
        "condition_at": _number(row, "condition_at", row.condition_at),
        "event_timeline_end": _number(row, "event_timeline_end", row.event_timeline_end),
        "kill_at": _number(row, "kill_at", row.kill_at),
        "duration": _number(row, "duration", row.event_timeline_end),
        "events": [event.as_json() for event in events],
        "annotator_notes": row.annotator_notes,
        "taxonomy": row.taxonomy,
        "eval_sql": row.eval_sql,
        "solution": row.solution,
    }
    order = list(row.key_order or (DEV_KEY_ORDER if row.is_dev else DEFAULT_KEY_ORDER))
    if "duration" in order and row.kill_at is not None and row.kill_at != row.event_timeline_end:
        # The legacy field stands for both bounds; once they differ, write both.
        at = order.index("duration")
        order[at : at + 1] = ["event_timeline_end"] + ([] if row.is_dev else ["kill_at"])
    # Fields an author filled in after import are added (at the end) rather than lost.
    if row.watch_page and "watch_page" not in order:
        order.insert(order.index("start_page") + 1 if "start_page" in order else 0, "watch_page")
    for key, present in (
        ("eval_sql", bool(row.eval_sql)),
        ("solution", bool(row.solution)),
        ("annotator_notes", bool(row.annotator_notes)),
    ):
        if present and key not in order:
            order.append(key)
    document = {}
    for key in order:
        if key in KNOWN_KEYS:
            if key == "solution" and not row.key_order and not row.solution:
                continue
            if key == "watch_page" and not row.watch_page:
                continue  # optional: a file without one is written without one
            document[key] = values[key]
        elif key in (row.extra or {}):
            document[key] = row.extra[key]
    for key, value in (row.extra or {}).items():
        document.setdefault(key, value)
    return document


def scenario_text(row: Scenario, events: list[TimelineEvent] | None = None) -> str:
    """The file text for `row`: its original bytes while unedited, else json.dump(indent=2)."""
    text = render_json(scenario_document(row, events))
    if row.original_text and sha256(text) == row.original_canonical_sha256:
        return row.original_text
    return text


def parsed_scenario(row: Scenario, events: list[TimelineEvent] | None = None) -> ParsedScenario:
    """The row validated by the format module (raises ScenarioError)."""
    document = scenario_document(row, events)
    source = f"scenario {row.path}"
    if row.is_dev:
        return parse_dev_scenario(document, source=source)
    return parse_scenario(document, source=source)


def run_spec(row: Scenario) -> dict[str, Any]:
    """What events.lifecycle.create_run expects: Scenario.to_run_spec of the validated row."""
    return parsed_scenario(row).to_run_spec()


def save_scenario_file(scenario_file: ScenarioFile) -> Scenario:
    """Insert or replace the row for this path, with its timeline."""
    new = scenario_file.row
    with transaction.atomic():
        row = Scenario.objects.filter(path=new.path).first()
        if row is not None:
            new.pk = row.pk
        canonical = render_json(scenario_document(new, scenario_file.events))
        if canonical != scenario_file.text:
            # e.g. a stray space in upstream's microfy/lyric-whiskey-relative-active.json
            new.original_text = scenario_file.text
            new.original_canonical_sha256 = sha256(canonical)
        else:
            new.original_text = new.original_canonical_sha256 = ""
        new.file_sha256 = sha256(scenario_file.text)  # row and file agree as of now
        new.save()
        TimelineEvent.objects.filter(scenario=new).delete()
        for event in scenario_file.events:
            event.scenario = new
        TimelineEvent.objects.bulk_create(scenario_file.events)
    return new


def scenario_files(root: Path) -> list[Path]:
    return sorted(p for p in root.rglob("*.json") if p.is_file())
