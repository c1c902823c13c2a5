"""Distractors cost: an agent that never monitors — it performs the task's action on every item
there is, then reports at the deadline — passes none of our active scenarios.

"Every item": each step of the scenario's solution is performed once per id of its kind in the
grading database (every track for `like_track`, every message for a reply, every stock for an
order, …), on a run advanced to `kill_at`; then the agent contacts and the run is graded. Each
active scenario's eval_sql must therefore reject the action on distractors and on items that
were there before the trigger (its annotator_notes say how). Ours only: the original
benchmark's tasks have no such clause.
"""

from __future__ import annotations

import contextlib
import re
import sqlite3
from collections.abc import Iterator

import pytest

from events import lifecycle
from events.commands import perform_action
from events.evaluation import evaluate, grading_snapshot
from events.models import Run
from events.registry import ActionRejected, PayloadError
from tests.conftest import OUR_SCENARIOS
from tests.environments.cases import params
from tests.environments.oracle import browser, contact

pytestmark = pytest.mark.django_db

# The benchmark's scenarios/ only, not the test-only ones (tests/environments/scenarios/).
BENCHMARK_ACTIVE = [
    param
    for param in params(noop=False, needs_action=True, upstream=False)
    if param.values[0].path.is_relative_to(OUR_SCENARIOS)
]

# Kinds of id whose items are listed under another name in the grading database.
ALSO = {
    "user_id": ("SELECT authorId FROM posts", "SELECT authorId FROM stories"),
    "conversation_id": ("SELECT id FROM conversations", "SELECT id FROM messages"),
}


def grading_database(run: Run) -> sqlite3.Connection:
    conn = sqlite3.connect(":memory:")
    grading_snapshot(run).write(conn)
    return conn


def ids_of_kind(conn: sqlite3.Connection, key: str) -> set:
    """Every value a payload field `key` (`track_id`, `symbol`, …) can take: the columns of
    that name (or its camelCase), the `id` of the tables named after it, and ALSO."""
    camel = re.sub(r"_(\w)", lambda m: m.group(1).upper(), key)
    prefix = key.removesuffix("_id")
    values: set = set()
    tables = [name for (name,) in conn.execute("SELECT name FROM sqlite_master WHERE type='table'")]
    for table in tables:
        for column in (row[1] for row in conn.execute(f'PRAGMA table_info("{table}")')):
            named = column in (key, camel)
            own_id = column == "id" and table.startswith(prefix) and "_" not in table
            if named or own_id:
                values |= {v for (v,) in conn.execute(f'SELECT "{column}" FROM "{table}"')}
    for sql in ALSO.get(key, ()):
        with contextlib.suppress(sqlite3.OperationalError):  # not this environment's table
            values |= {v for (v,) in conn.execute(sql)}
    values.discard(None)
    return values


def on_every_item(conn: sqlite3.Connection, step: dict) -> Iterator[dict]:
    """The step's payload once per item: a reply to every message, else every id of the kind
    of its first id field (a step without one, as it is)."""
    payload = step["payload"]
    if "reply_to" in payload:
        for message, conversation in conn.execute("SELECT id, conversationId FROM messages"):
            yield {**payload, "conversation_id": conversation, "reply_to": message}
        return
    keys = [key for key in payload if key.endswith("_id") or key == "symbol"]
    if not keys:
        yield payload
        return
    for value in sorted(ids_of_kind(conn, keys[0]), key=str):
        yield {**payload, keys[0]: value}


@pytest.mark.parametrize("case", BENCHMARK_ACTIVE)
def test_acting_on_every_item_and_reporting_at_the_deadline_fails(case, start):
    scenario, run = start(case)
    lifecycle.advance(run, scenario.kill_at)
    conn = grading_database(run)
    acted = 0
    for step in scenario.solution:
        for payload in on_every_item(conn, step):
            try:
                perform_action(run, step["action"], payload)
                acted += 1
            except (ActionRejected, PayloadError):
                pass  # already done, or not possible on this item
    assert acted >= len(scenario.solution)
    contact(browser(), run)
    verdict = evaluate(run)
    assert verdict.success is False, (
        f"{scenario.id}: {acted} actions on every item then a contact at {scenario.kill_at:g} s "
        f"pass ({verdict.detail}); its eval_sql must reject the action on distractors"
    )
