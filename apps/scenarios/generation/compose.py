"""One candidate scenario from a family's template and a random draw.

What varies (`ASPECTS`, all by default; the admin's "Generate variants…" may pick):

- timing — the trigger arrives at a new `condition_at` drawn from the environment's arrival
  process (apps.scenarios.generation.arrivals); the story events keep their order, moved by a
  piecewise-linear warp of the timeline that sends the old condition time to the new one (what
  came before the trigger still comes before it, in the same proportions); background events
  are re-timed by the process (bursts, morning peaks, jumps);
- distractors — some background items are replaced by other catalog items of the same kind and
  one to three more arrive, preferring near misses: the items that share the most catalog fields
  with the trigger (the right sender with the wrong subject, the same channel, the same
  symbol…). A near miss that satisfies the condition is not avoided here: the proofs discard it;
- phrasing — the prompt reworded (apps.scenarios.generation.phrasing).

A withheld family's candidate drops the trigger: it is written as a no-op (no `condition_at`, no
`eval_sql`, no solution), and proven with the template's `eval_sql`, which must never hold.
"""

from __future__ import annotations

import copy
import random
from dataclasses import dataclass
from typing import Any

from apps.scenarios.generation.arrivals import process_for
from apps.scenarios.generation.phrasing import rephrase
from apps.scenarios.generation.templates import Template, item_of
from events.catalog import Catalog
from events.registry import get_environment

ASPECTS = ("timing", "distractors", "phrasing")
NEAR_MISS_SHARE = 0.6  # of added or replacing items, drawn from the trigger's closest kin
NEAR_MISS_POOL = 5  # how many of the closest kin a near miss is drawn from
REPLACE_SHARE = 0.4  # of background items replaced by another of the same kind


@dataclass(frozen=True)
class Candidate:
    template: Template
    document: dict[str, Any]  # the scenario as it would be written
    proven: dict[str, Any]  # what the proofs play: a withheld no-op keeps the template's eval_sql
    aspects: tuple[str, ...]
    added: tuple[str, ...]  # catalog items brought in as distractors


def _warp(time: float, anchor: float, target: float, end: float) -> float:
    """Piecewise linear: 0 -> 0, anchor -> target, end -> end; later times unchanged."""
    if time <= 0:
        return 0.0
    if time <= anchor:
        moved = time * target / anchor
    elif time <= end:
        moved = target + (time - anchor) * (end - target) / (end - anchor)
    else:
        moved = time
    return max(0.01, round(moved, 2))


def _kin(catalog: Catalog, environment: str, table: str, trigger_id: str, pool: list[str]):
    """`pool` sorted by how many catalog fields each item shares with the trigger item."""
    records = catalog.table(environment, table)
    trigger = records.get(trigger_id) or {}

    def shared(item_id: str) -> int:
        record = records.get(item_id) or {}
        return sum(1 for k, v in trigger.items() if k != "id" and record.get(k) == v)

    return sorted(pool, key=lambda i: -shared(i))


class _Distractors:
    """Draws distractor items without repeats: near misses of the trigger first, else any."""

    def __init__(self, template: Template, catalog: Catalog, pool: dict[str, list[str]], rng):
        self.rng, self.pool = rng, {k: list(v) for k, v in pool.items()}
        self.kin: dict[str, list[str]] = {}
        events = template.document["events"]
        trigger = events[template.trigger] if template.trigger is not None else None
        item = item_of(trigger) if trigger else None
        if item and trigger["type"] in self.pool:
            refs = get_environment(template.environment).event_types[trigger["type"]].catalog_refs
            table = refs.get(item[0])
            if table:
                kin = _kin(
                    catalog, template.environment, table, item[1], self.pool[trigger["type"]]
                )
                self.kin[trigger["type"]] = kin[:NEAR_MISS_POOL]
        self.used: list[str] = []

    def draw(self, kind: str) -> str | None:
        near = [i for i in self.kin.get(kind, []) if i not in self.used]
        rest = [i for i in self.pool.get(kind, []) if i not in self.used]
        choices = near if near and self.rng.random() < NEAR_MISS_SHARE else rest
        if not choices:
            return None
        chosen = self.rng.choice(choices)
        self.used.append(chosen)
        return chosen


def compose(
    template: Template,
    rng: random.Random,
    *,
    scenario_id: str,
    catalog: Catalog,
    pool: dict[str, list[str]],
    aspects: tuple[str, ...] = ASPECTS,
    note: str = "",
) -> Candidate:
    document = copy.deepcopy(template.document)
    process = process_for(template.environment)
    end = float(document["event_timeline_end"])
    events: list[dict[str, Any]] = document["events"]
    condition = document.get("condition_at")
    story_times = [float(events[i]["time"]) for i in sorted(template.story)]
    anchor = float(condition) if condition is not None else _middle(story_times, end)
    target = process.condition_time(rng) if "timing" in aspects else anchor

    timed: list[tuple[float, int, dict[str, Any]]] = []  # (time, file order, event)
    background = []
    for i, event in enumerate(events):
        if template.withheld and i == template.trigger:
            continue
        if i in template.story or "timing" not in aspects:
            timed.append((_warp(float(event["time"]), anchor, target, end), i, event))
        else:
            background.append((i, event))
    if background:
        times = process.arrival_times(rng, len(background), 0.5, end - 1.0)
        rng.shuffle(background)
        timed += [(t, i, e) for t, (i, e) in zip(times, background, strict=True)]

    added: list[str] = []
    if "distractors" in aspects and pool:
        timed = _with_distractors(template, timed, rng, catalog, pool, process, end, added)

    timed.sort(key=lambda entry: (entry[0], entry[1]))
    document["events"] = [{**event, "time": time} for time, _, event in timed]
    document["id"] = scenario_id
    if "phrasing" in aspects:
        document["prompt"] = rephrase(document["prompt"], rng)
    notes = [document.get("annotator_notes") or "", note]
    if template.withheld:
        withheld = item_of(events[template.trigger]) if template.trigger is not None else None
        notes.append(
            f"No-op: the trigger ({withheld[1] if withheld else 'its event'}) is withheld, so "
            "the condition never holds."
        )
        document["condition_at"] = None
        document["solution"] = []
        proven = copy.deepcopy(document)
        document.pop("eval_sql", None)
        document.pop("contact_rubric", None)
    else:
        if condition is not None:
            document["condition_at"] = target
        proven = document
    if added:
        notes.append(f"Distractors added: {', '.join(added)}.")
    document["annotator_notes"] = " ".join(n for n in notes if n)
    if template.withheld:
        proven["annotator_notes"] = document["annotator_notes"]
    return Candidate(template, document, proven, tuple(aspects), tuple(added))


def _middle(times: list[float], end: float) -> float:
    later = sorted(t for t in times if t > 0)
    return later[len(later) // 2] if later else end / 2


def _with_distractors(template, timed, rng, catalog, pool, process, end, added):
    draws = _Distractors(template, catalog, pool, rng)
    out = []
    for time, order, event in timed:
        item = item_of(event)
        if order not in template.story and item and rng.random() < REPLACE_SHARE:
            other = draws.draw(event["type"])
            if other is not None:
                event = {**event, "payload": {item[0]: other}}
                added.append(other)
        out.append((time, order, event))
    kinds = sorted(pool)
    for extra in range(rng.randint(1, 3)):
        kind = rng.choice(kinds)
        other = draws.draw(kind)
        if other is None:
            continue
        key = _payload_key(template, kind)
        (time,) = process.arrival_times(rng, 1, 0.5, end - 1.0)
        out.append((time, len(template.document["events"]) + extra, _event(kind, key, other)))
        added.append(other)
    return out


def _payload_key(template: Template, kind: str) -> str:
    for event in template.document["events"]:
        item = item_of(event)
        if event["type"] == kind and item:
            return item[0]
    raise ValueError(f"{template.family}: no {kind} event to copy the payload of")


def _event(kind: str, key: str, item_id: str) -> dict[str, Any]:
    return {"time": 0.0, "type": kind, "payload": {key: item_id}}
