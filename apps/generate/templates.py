"""Task families, read from our hand-written scenarios.

Every hand-written scenario is the template of one family, named by its file (`micromail`'s
`sender-absolute-passive.json` is family `sender-absolute-passive`): the paper's taxonomy is in
it (active/passive, absolute/relative, no-op) and so is the environment's condition kind (a
sender, a keyword, a count, a threshold, a date…), its eval_sql, its solution and its
hand-picked near misses. Each passive template also gives a no-op family, `<family>-withheld`:
the same story with the trigger withheld, so the condition never holds (a count one short, the
awaited sender never writing).

A template's timeline splits in two. *Story* events are kept in their order and moved with the
trigger: the preload, every event that is not a single catalog item arriving (price and star
waypoints), the trigger itself and every item its eval_sql, solution, notes or prompt names (the
author's near misses). *Background* events — items arriving that nothing names — are what the
generator re-times, replaces and adds to.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from apps.scenarios.format import DEV_FILENAME, ScenarioError, parse_scenario, read_json_file
from events.catalog import Catalog
from events.registry import UnknownEnvironment, get_environment

WITHHELD = "-withheld"


@dataclass(frozen=True)
class Template:
    environment: str
    family: str
    source: str  # the template's file, relative to the scenario folder
    document: dict[str, Any]
    story: frozenset[int]  # indices of story events (see module doc); the rest is background
    trigger: int | None  # index of the event that makes the condition hold (None: a no-op)
    withheld: bool = False  # a no-op family made from a passive template

    @property
    def kind(self) -> str:
        """noop, passive or active: how the family's scenarios are graded."""
        if self.withheld or self.document.get("condition_at") is None:
            return "noop"
        return (self.document.get("taxonomy") or {}).get("monitoring_approach") or "passive"

    @property
    def milestone(self) -> str:
        return (self.document.get("taxonomy") or {}).get("milestone_type") or "absolute"


def item_of(event: dict[str, Any]) -> tuple[str, str] | None:
    """(payload field, id) when the event is one catalog item arriving, else None."""
    payload = event.get("payload") or {}
    if len(payload) == 1:
        ((key, value),) = payload.items()
        if key.endswith("_id") and isinstance(value, str):
            return key, value
    return None


def _token(item_id: str) -> re.Pattern:
    """`item_id` as a whole token (`base-1` is not in `base-12`)."""
    return re.compile(rf"(?<![\w-]){re.escape(item_id)}(?![\w-])")


def mentions(text: str, item_id: str) -> bool:
    """Whether `text` names `item_id` as a whole token."""
    return _token(item_id).search(text) is not None


def renamed(text: str, old: str, new: str) -> str:
    """`text` with every whole-token `old` made `new`."""
    return _token(old).sub(lambda _: new, text)


def _named_text(document: dict[str, Any]) -> str:
    parts = [
        document.get("eval_sql") or "",
        json.dumps(document.get("solution") or []),
        document.get("annotator_notes") or "",
        document.get("prompt") or "",
    ]
    return "\n".join(parts)


def _split(document: dict[str, Any]) -> tuple[frozenset[int], int | None]:
    events, condition = document["events"], document.get("condition_at")
    named = _named_text(document)
    trigger = None
    if condition is not None:
        at_condition = [i for i, e in enumerate(events) if float(e["time"]) == float(condition)]
        trigger = at_condition[-1] if at_condition else None
    story = set()
    for i, event in enumerate(events):
        item = item_of(event)
        if float(event["time"]) == 0 or item is None or i == trigger or mentions(named, item[1]):
            story.add(i)
    return frozenset(story), trigger


def template_of(document: dict[str, Any], environment: str, source: str) -> Template:
    """The family of one scenario document (a file's, or the admin's row), named by its
    file `source` (`micromail/sender-absolute-passive.json`)."""
    story, trigger = _split(document)
    family = source.rsplit("/", 1)[-1].removesuffix(".json")
    return Template(environment, family, source, document, story, trigger)


def read_templates(root: Path) -> list[Template]:
    """Every family of the hand-written scenarios under `root` (sorted by environment, file),
    each passive template followed by its withheld no-op family. Files that do not parse, dev
    files and environments without an app are skipped: they cannot be proven."""
    templates: list[Template] = []
    for path in sorted(root.glob("*/*.json")):
        if path.name == DEV_FILENAME:
            continue
        try:
            _, document = read_json_file(path)
            parsed = parse_scenario(document, source=str(path))
            get_environment(parsed.environment)
        except (ScenarioError, UnknownEnvironment):
            continue
        template = template_of(document, parsed.environment, path.relative_to(root).as_posix())
        templates.append(template)
        if template.kind == "passive" and template.trigger is not None:
            templates.append(
                Template(
                    template.environment,
                    template.family + WITHHELD,
                    template.source,
                    document,
                    template.story - {template.trigger},
                    template.trigger,
                    withheld=True,
                )
            )
    return templates


def item_pool(template: Template, catalog: Catalog) -> dict[str, list[str]]:
    """Per event type of an item arriving in the template, the catalog items that may arrive
    instead of a background one or in addition: every id of the type's catalog table that the
    template does not mention anywhere (so never its trigger, a preloaded item or one of its
    near misses), in catalog order."""
    environment = get_environment(template.environment)
    text = json.dumps(template.document)
    pool: dict[str, list[str]] = {}
    for event in template.document["events"]:
        item = item_of(event)
        if item is None or event["type"] in pool:
            continue
        table = environment.event_types[event["type"]].catalog_refs.get(item[0])
        if table is None:
            continue
        ids = catalog.table(template.environment, table)
        pool[event["type"]] = [i for i in ids if not mentions(text, i)]
    return pool
