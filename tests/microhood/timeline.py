"""Folding a MicroHood scenario file without a database, as the core folds its log."""

from __future__ import annotations

import json
from pathlib import Path

from apps.microhood.environment import MICROHOOD
from events.catalog import Catalog, load_catalog
from events.registry import LoggedEvent

ROOT = Path(__file__).resolve().parents[2]
OUR_CATALOG = ROOT / "fixtures"
OUR_SCENARIOS = ROOT / "scenarios" / "microhood"


def scenario(path: Path) -> dict:
    return json.loads(path.read_text(encoding="utf-8"))


def events(data: dict) -> list[LoggedEvent]:
    timeline = sorted(data["events"], key=lambda e: e["time"])  # stable, as /init sorts
    return [
        LoggedEvent(seq, float(e["time"]), "scenario", e["type"], e["payload"])
        for seq, e in enumerate(timeline, 1)
    ]


def fold_until(data: dict, now: float, catalog: Catalog | None = None, actions=()):
    """The state after every scenario event with time ≤ now (and `actions`: LoggedEvents)."""
    catalog = catalog or load_catalog(OUR_CATALOG)
    due = [e for e in events(data) if e.at <= now]
    due = sorted([*due, *actions], key=lambda e: (e.at, e.seq))
    state, _ = MICROHOOD.fold(MICROHOOD.initial_state(catalog), due)
    return state
