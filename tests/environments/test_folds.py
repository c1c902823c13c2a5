"""The "verify projection" tests, for every registered environment, over each of our scenarios
played with its solution interleaved:

- the state the real cache hands out (fast-forwarded by `folded_state` after every event) is
  the fold from scratch of the same log position — state and baselines, order included;
- so is every past position, reached by fast-forwarding one event at a time;
- applying each logged event to the previous state (`Environment.fold` of one event) equals
  folding the prefix.

And the check is shown to fail: with a cache that drops `action` events while fast-forwarding,
and with two deliveries swapped, which `==` does not notice.
"""

from __future__ import annotations

import pytest
from django.conf import settings

from apps.micromail.environment import MICROMAIL
from apps.micromail.state import select
from apps.scenarios.format import Scenario
from events import lifecycle, projection
from events.catalog import load_catalog
from events.commands import perform_action
from events.models import EventKind, Run
from events.projection import (
    Folded,
    clear_cache,
    fold_from_scratch,
    folded_state,
    initial_state,
    logged_events,
)
from events.registry import EMPTY, ActionRejected, LoggedEvent, environment_names, get_environment
from tests.environments import folds
from tests.environments.cases import our_cases, params
from tests.environments.folds import (
    FoldMismatch,
    assert_same,
    assert_same_fold,
    canonical,
    surely_same,
)

pytestmark = pytest.mark.django_db

OUR_SCENARIOS = params(upstream=False)


def play(run: Run, scenario: Scenario) -> list[Folded]:
    """Advance the virtual clock through the timeline, doing each solution step as soon as the
    state allows it; after every event, read the state as a page would (so the cache
    fast-forwards). Returns each fold the cache handed out."""
    handed_out = [folded_state(run)]
    pending = list(scenario.solution)

    def act() -> None:
        nonlocal pending
        left = []
        for step in pending:
            try:
                perform_action(run, step["action"], step["payload"])
            except ActionRejected:
                left.append(step)
                continue
            handed_out.append(folded_state(run))
        pending = left

    act()
    for at in sorted({e["time"] for e in run.timeline if 0 < e["time"] <= run.event_timeline_end}):
        lifecycle.advance(run, at)
        handed_out.append(folded_state(run))
        act()
    assert pending == [], f"solution steps never possible: {pending}"
    return handed_out


def check_cached_folds(run: Run, scenario: Scenario) -> None:
    """Every fold the cache hands out, during play and afterwards at each position, is the fold
    from scratch of its position (FoldMismatch otherwise)."""
    for folded in play(run, scenario):
        assert_same_fold(fold_from_scratch(run, folded.seq), folded, where=f"seq {folded.seq}")
    clear_cache()
    last = logged_events(run.pk)[-1].seq
    for seq in range(1, last + 1):  # the first from scratch, then one event at a time
        where = f"seq {seq} (one at a time)"
        assert_same_fold(fold_from_scratch(run, seq), folded_state(run, seq), where=where)
    assert_same_fold(fold_from_scratch(run), folded_state(run), where="the whole log")


@pytest.mark.parametrize("case", OUR_SCENARIOS)
def test_the_cached_fold_equals_a_fold_from_scratch_at_every_position(case, start):
    scenario, run = start(case)
    check_cached_folds(run, scenario)


@pytest.mark.parametrize("case", OUR_SCENARIOS)
def test_applying_each_event_to_the_previous_state_equals_folding_the_prefix(case, start):
    scenario, run = start(case)
    play(run, scenario)
    environment = get_environment(run.environment)
    state, baselines = initial_state(run), EMPTY
    for event in logged_events(run.pk):
        state, baselines = environment.fold(state, [event], baselines)
        expected = fold_from_scratch(run, event.seq)
        assert_same(expected.state, state, what=f"seq {event.seq}: the state")
        assert_same(expected.baselines, baselines, what=f"seq {event.seq}: the baselines")


# --- the check can fail ------------------------------------------------------------------------


@pytest.fixture
def cache_dropping_actions(monkeypatch):
    """Break the projection on purpose: its fast-forward (a read after a cached position) loses
    every `action` event; a fold from scratch (from position 0) still sees them."""
    real = projection.logged_events

    def dropping(run_id: int, after: int = 0, upto: int | None = None) -> list[LoggedEvent]:
        events = real(run_id, after, upto)
        return events if after == 0 else [e for e in events if e.kind != EventKind.ACTION]

    monkeypatch.setattr(projection, "logged_events", dropping)


@pytest.mark.parametrize("environment", environment_names())
def test_a_cache_that_drops_actions_is_caught(environment, start, cache_dropping_actions):
    acting = [case for case in our_cases(environment) if case.solution()]
    if not acting:
        pytest.skip(f"no scenario of ours for {environment} has a solution (no action to drop)")
    scenario, run = start(acting[0])
    with pytest.raises(FoldMismatch):
        check_cached_folds(run, scenario)


def deliveries(*email_ids: str) -> list[LoggedEvent]:
    """Messages arriving in this order, all at the same second."""
    return [
        LoggedEvent(seq, 60.0, EventKind.SCENARIO, "new_email", {"email_id": email_id})
        for seq, email_id in enumerate(email_ids, start=1)
    ]


def test_two_deliveries_in_another_order_are_caught_where_equality_misses_them():
    empty = MICROMAIL.initial_state(load_catalog(settings.SENTINEL_CATALOG_DIR))
    first, _ = MICROMAIL.fold(empty, deliveries("base-44", "base-45"))
    swapped, _ = MICROMAIL.fold(empty, deliveries("base-45", "base-44"))
    assert swapped == first  # dict equality ignores order…
    # …yet the order shows: same arrival time, so the later delivery is listed on top.
    assert select(first, folder="inbox") != select(swapped, folder="inbox")
    with pytest.raises(FoldMismatch, match="the same keys in another order"):
        assert_same(first, swapped, what="the mailbox")


@pytest.mark.parametrize(
    ("expected", "actual"),
    [
        ({"a": 1, "b": 2}, {"b": 2, "a": 1}),  # the same keys in another order
        ({"a": 1}, {"a": 1.0}),  # equal, yet another type
        ([1, True], [1, 1]),
        ({1, 2}, {1.0, 2}),
        ({"x"}, {"y"}),
        ((1, 2), [1, 2]),
    ],
)
def test_the_fast_comparison_never_calls_different_folds_the_same(expected, actual):
    assert canonical(expected) != canonical(actual)
    assert not surely_same(expected, actual)
    with pytest.raises(FoldMismatch):
        assert_same(expected, actual, what="the value")


def test_the_fast_comparison_sees_two_equal_folds_without_canonical_forms(monkeypatch):
    empty = MICROMAIL.initial_state(load_catalog(settings.SENTINEL_CATALOG_DIR))
    first, _ = MICROMAIL.fold(empty, deliveries("base-44", "base-45"))
    again, _ = MICROMAIL.fold(empty, deliveries("base-44", "base-45"))
    assert first is not again and canonical(first) == canonical(again)
    assert surely_same(first, again)
    monkeypatch.setattr(folds, "canonical", None)  # the slow path is not taken
    assert_same(first, again, what="the mailbox")
