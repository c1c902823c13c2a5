"""Digests of a run's log and state, recorded verdicts, and the replay check.

The state digest is a sha256 over a canonical JSON dump of every table of the grading database
(session_meta with its baselines, and the environment's tables), so two folds agree exactly when
what eval_sql could see agrees. The log digest covers every logged field except wall-clock bookkeeping.
"""

from __future__ import annotations

import hashlib
import json
import sqlite3
from dataclasses import dataclass, field
from typing import Any

from apps.replay.models import VERDICT_FIELDS, RunVerdict
from events.evaluation import GradingSnapshot, grade, grading_snapshot
from events.models import Event, Run
from events.projection import forget

LOG_FIELDS = ("seq", "at", "kind", "type", "payload", "timeline_index")


def _canonical(value: Any) -> str:
    return json.dumps(value, sort_keys=True, separators=(",", ":"), default=_encode)


def _encode(value: Any) -> Any:
    if isinstance(value, bytes):
        return {"bytes": value.hex()}
    raise TypeError(f"cannot encode {type(value).__name__}")


def tables_of(snapshot: GradingSnapshot) -> dict[str, dict[str, Any]]:
    """Every table of the grading database: name → {columns, rows (sorted)}."""
    conn = sqlite3.connect(":memory:")
    try:
        snapshot.write(conn)
        names = [
            r[0]
            for r in conn.execute(
                "SELECT name FROM sqlite_master WHERE type = 'table' ORDER BY name"
            )
        ]
        tables = {}
        for name in names:
            cursor = conn.execute(f'SELECT * FROM "{name}"')
            columns = [d[0] for d in cursor.description]
            rows = sorted((list(row) for row in cursor.fetchall()), key=_canonical)
            tables[name] = {"columns": columns, "rows": rows}
        return tables
    finally:
        conn.close()


def state_digest(snapshot: GradingSnapshot) -> str:
    return hashlib.sha256(_canonical(tables_of(snapshot)).encode()).hexdigest()


def log_digest(run: Run, upto: int | None = None) -> tuple[str, int]:
    rows = Event.objects.filter(run_id=run.pk)
    if upto is not None:
        rows = rows.filter(seq__lte=upto)
    digest = hashlib.sha256()
    count = 0
    for row in rows.order_by("seq").values_list(*LOG_FIELDS):
        digest.update(_canonical(list(row)).encode())
        digest.update(b"\n")
        count += 1
    return digest.hexdigest(), count


@dataclass(frozen=True)
class Refold:
    """A from-scratch refold of a run: its verdict, state digest and log digest now."""

    success: bool
    detail: str
    graded_at_seq: int | None
    event_count: int
    state_digest: str
    log_digest: str

    def as_dict(self) -> dict[str, Any]:
        return {name: getattr(self, name) for name in VERDICT_FIELDS}


def refold(run: Run) -> Refold:
    """Fold the whole log from scratch and grade it (read-only: the run is not completed)."""
    # Both fold through the projection cache: this run's entry goes, so they start from
    # nothing. Only this run's: clearing every run's would make each verdict recorded on a busy
    # server (bench validate closes dozens at once) refold every other open run from scratch.
    forget(run)
    snapshot = grading_snapshot(run)
    success, detail, _contacts, graded_at = grade(run)
    digest, count = log_digest(run)
    return Refold(
        success=success,
        detail=detail,
        graded_at_seq=graded_at,
        event_count=count,
        state_digest=state_digest(snapshot),
        log_digest=digest,
    )


def record_verdict(run: Run, *, source: str = "recorded") -> RunVerdict:
    result = refold(run)
    return RunVerdict.objects.create(run=run, source=source, **result.as_dict())


def latest_verdict(run: Run) -> RunVerdict | None:
    return RunVerdict.objects.filter(run=run).order_by("-id").first()


@dataclass
class ReplayReport:
    run: int
    recorded: dict[str, Any] | None
    replayed: dict[str, Any]
    differences: list[str] = field(default_factory=list)

    @property
    def matches(self) -> bool:
        return self.recorded is not None and not self.differences


COMPARED = (
    ("success", "verdict"),
    ("detail", "verdict detail"),
    ("graded_at_seq", "graded at log position"),
    ("event_count", "number of logged events"),
    ("log_digest", "log digest (an event row changed)"),
    ("state_digest", "final state digest"),
)


def replay(run: Run) -> ReplayReport:
    """Refold `run` from scratch and compare with its latest recorded verdict."""
    recorded = latest_verdict(run)
    replayed = refold(run).as_dict()
    report = ReplayReport(
        run=run.pk, recorded=recorded.as_dict() if recorded else None, replayed=replayed
    )
    if recorded is None:
        report.differences.append("no recorded verdict for this run (export or record one first)")
        return report
    for key, what in COMPARED:
        if report.recorded[key] != replayed[key]:
            report.differences.append(
                f"{what}: recorded {report.recorded[key]!r}, replayed {replayed[key]!r}"
            )
    return report
