"""One candidate scenario from a family's template and a random draw.

What varies (`ASPECTS`, all by default; the admin's "Generate variants…" may pick):

- timing — the trigger arrives at a new `condition_at` drawn from the environment's arrival
  process (apps.generate.arrivals); the story events keep their order, moved by a
  piecewise-linear warp of the timeline that sends the old condition time to the new one (what
  came before the trigger still comes before it, in the same proportions; waypoints inside a
  preload's payload too); background events are re-timed by the process (bursts, morning
  peaks, jumps), as many before the trigger as there were; an ephemeral condition's end
  (`condition_until`) moves by the same warp as what ends it;
- distractors — some background items are replaced by other catalog items of the same kind and
  one to three more arrive, preferring near misses: the items that share the most catalog fields
  with the trigger (the right sender with the wrong subject, the same channel, the same
  symbol…). A near miss that satisfies the condition is not avoided here: the proofs discard it;
- phrasing — the prompt reworded (apps.generate.phrasing);
- trigger — another catalog item of the trigger's kind arrives as the trigger, drawn from its
  closest kin (the same sender, channel, author…); wherever the scenario names the trigger by id
  (its eval_sql, its solution, the event that takes an ephemeral trigger away again) the new id
  takes its place. One that does not meet the condition
  (the keyword is not in its body) fails the proofs and is discarded.

A withheld family's candidate drops the trigger: it is written as a no-op (no `condition_at`, no
`eval_sql`, no solution), and proven with the template's `eval_sql`, which must never hold.
"""

from __future__ import annotations

import copy
import json
import random
from dataclasses import dataclass
from typing import Any

from apps.generate.arrivals import process_for
from apps.generate.phrasing import rephrase
from apps.generate.templates import Template, item_of, renamed
from events.catalog import Catalog
from events.registry import get_environment

ASPECTS = ("timing", "distractors", "phrasing", "trigger")
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


def waypoint_lists(event: dict[str, Any]):
    """Every [[time, value], …] list in the event's payload (`price_waypoints` per symbol,
    `star_waypoints`)."""
    for key, value in (event.get("payload") or {}).items():
        if not key.endswith("_waypoints"):
            continue
        yield from value.values() if isinstance(value, dict) else [value]


def _pin_waypoints(events: list[dict[str, Any]], at: float) -> None:
    """Add a waypoint at `at` on every trajectory that passes it between two waypoints, with
    the value it has there, so that warping the times keeps the value at `at` (in place)."""
    for event in events:
        for points in waypoint_lists(event):
            for i in range(len(points) - 1):
                (t0, v0), (t1, v1) = points[i], points[i + 1]
                if t0 < at < t1:
                    value = v0 + (v1 - v0) * (at - t0) / (t1 - t0)
                    both_int = isinstance(v0, int) and isinstance(v1, int)
                    points.insert(i + 1, [at, round(value) if both_int else round(value, 4)])
                    break


def _warp_waypoints(event: dict[str, Any], anchor: float, target: float, end: float):
    """The event with its payload's waypoint times warped as timeline times are."""
    if not any(True for _ in waypoint_lists(event)):
        return event
    event = copy.deepcopy(event)
    for points in waypoint_lists(event):
        points[:] = [[_warp(float(t), anchor, target, end), v] for t, v in points]
    return event


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

    def __init__(
        self, template: Template, catalog: Catalog, pool: dict[str, list[str]], rng, used=()
    ):
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
        self.used: list[str] = list(used)  # never drawn again (a swapped-in trigger)

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
    quiet: bool = False,
    stratum: int | None = None,
) -> Candidate:
    """A candidate of `template`'s family. `quiet`: the fallback when a full draw fails its
    proofs — the template's trigger, no distractors added, and the background moved with the
    story instead of re-timed (a count that the re-timed background reached early, a no-op it
    satisfied)."""
    document = copy.deepcopy(template.document)
    process = process_for(template.environment)
    end = float(document["event_timeline_end"])
    events: list[dict[str, Any]] = document["events"]
    condition = document.get("condition_at")
    story_times = [float(events[i]["time"]) for i in sorted(template.story)]
    anchor = float(condition) if condition is not None else _middle(story_times, end)
    target = process.condition_time(rng, stratum) if "timing" in aspects else anchor
    if condition is not None and template.trigger is None:
        # A condition met between timeline entries (a price or a star count crossing between
        # waypoints): the trajectory must pass the old condition time exactly where it did.
        _pin_waypoints(events, anchor)

    timed: list[tuple[float, int, dict[str, Any]]] = []  # (time, file order, event)
    background = []
    for i, event in enumerate(events):
        if template.withheld and i == template.trigger:
            continue
        if i in template.story or quiet or "timing" not in aspects:
            event = _warp_waypoints(event, anchor, target, end)
            timed.append((_warp(float(event["time"]), anchor, target, end), i, event))
        else:
            background.append((i, event))
    # Re-timed on each side of the trigger as many as were there: a count the trigger completes
    # stays one short before it.
    for side, low, high in ((True, 0.5, target - 0.01), (False, target + 0.01, end - 1.0)):
        group = [(i, e) for i, e in background if (float(e["time"]) <= anchor) == side]
        if group:
            times = process.arrival_times(rng, len(group), low, high)
            rng.shuffle(group)
            timed += [(t, i, e) for t, (i, e) in zip(times, group, strict=True)]

    swapped = None
    if "trigger" in aspects and not quiet and not template.withheld:
        swapped = _swap_trigger(template, document, timed, rng, catalog, pool)
    added: list[str] = []
    if "distractors" in aspects and pool and not quiet:
        used = [swapped[1]] if swapped else []
        timed = _with_distractors(template, timed, rng, catalog, pool, process, end, added, used)

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
        if document.get("condition_until") is not None:
            # An ephemeral condition ends where its retraction went, moved with the story.
            document["condition_until"] = _warp(
                float(document["condition_until"]), anchor, target, end
            )
        proven = document
    if swapped:
        notes.append(f"The trigger is {swapped[1]} (the template's: {swapped[0]}).")
    if added:
        notes.append(f"Distractors added: {', '.join(added)}.")
    document["annotator_notes"] = " ".join(n for n in notes if n)
    if template.withheld:
        proven["annotator_notes"] = document["annotator_notes"]
    return Candidate(template, document, proven, tuple(aspects), tuple(added))


def _middle(times: list[float], end: float) -> float:
    later = sorted(t for t in times if t > 0)
    return later[len(later) // 2] if later else end / 2


def _swap_trigger(template, document, timed, rng, catalog, pool) -> tuple[str, str] | None:
    """Another item of the trigger's kind as the trigger (see the module doc): (old id, new
    id), or None when the trigger is no catalog item or none of its kind is free."""
    if template.trigger is None:
        return None
    event = template.document["events"][template.trigger]
    item = item_of(event)
    if item is None or not pool.get(event["type"]):
        return None
    table = get_environment(template.environment).event_types[event["type"]].catalog_refs
    if item[0] not in table:
        return None
    kin = _kin(catalog, template.environment, table[item[0]], item[1], pool[event["type"]])
    new = rng.choice(kin[: 2 * NEAR_MISS_POOL])
    for i, (time, order, entry) in enumerate(timed):
        # The trigger, and what later happens to it (an ephemeral one's retraction), follow it.
        named = item_of(entry)
        if order == template.trigger or (named is not None and named[1] == item[1]):
            timed[i] = (time, order, {**entry, "payload": {named[0] if named else item[0]: new}})
    for key in ("eval_sql", "solution", "contact_rubric"):
        if document.get(key):
            text = json.dumps(document[key])
            document[key] = json.loads(renamed(text, item[1], new))
    return item[1], new


def _with_distractors(template, timed, rng, catalog, pool, process, end, added, used=()):
    draws = _Distractors(template, catalog, pool, rng, used)
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
