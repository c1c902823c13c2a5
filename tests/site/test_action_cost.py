"""What a page action costs: it decides on the state its request already folded and applies its
one logged event — one firing of due entries, at most two folds, at most six SQL statements —
and the state it leaves is the state a fold of the log gives."""

from __future__ import annotations

import pytest
from django.test import Client

from events import commands, lifecycle, projection
from events.models import ClockMode
from events.projection import fold_from_scratch, folded_state

pytestmark = pytest.mark.django_db


@pytest.fixture
def counted(monkeypatch):
    """Calls of fire_due and of the fold, counted where the request path makes them."""
    calls = {"fire_due": 0, "fold": 0}

    def counting(name, module, attribute):
        original = getattr(module, attribute)

        def wrapper(*args, **kwargs):
            calls[name] += 1
            return original(*args, **kwargs)

        monkeypatch.setattr(module, attribute, wrapper)

    counting("fire_due", commands, "fire_due")
    counting("fold", commands, "folded_state")
    counting("fold", projection, "folded_state")
    return calls


@pytest.fixture
def tally_run(tally_spec):
    return lifecycle.create_run(tally_spec(), clock_mode=ClockMode.VIRTUAL)


def poke(run, n: int = 3):
    return Client().post(f"/r/{run.token}/tally/poke", {"n": str(n)})


def test_a_page_action_fires_once_folds_at_most_twice_and_runs_six_statements(
    tally_run, counted, django_assert_max_num_queries
):
    Client().get(f"/r/{tally_run.token}/tally/")  # the page is open: the usual case
    counted.update(fire_due=0, fold=0)
    with django_assert_max_num_queries(6):
        response = poke(tally_run)
    assert response.status_code == 302
    assert counted["fire_due"] == 1
    assert counted["fold"] <= 2


def test_the_state_an_action_leaves_is_the_fold_of_the_log(tally_run):
    Client().get(f"/r/{tally_run.token}/tally/")
    poke(tally_run, 3)
    poke(tally_run, 4)
    cached = folded_state(tally_run)
    scratch = fold_from_scratch(tally_run)
    assert cached.state == scratch.state
    assert (cached.seq, cached.live_seq) == (scratch.seq, scratch.live_seq)
    assert [n for source, n, _ in cached.state.entries if source == "poke"] == [3, 4]


def test_an_action_after_someone_elses_event_folds_it_in(tally_run):
    """A scenario event fired between the page's fold and its action (the ticker, another
    tab) is in the state the action leaves: the shortcut applies only to the next entry."""
    lifecycle.advance(tally_run, 5.0)
    folded = folded_state(tally_run)
    lifecycle.advance(tally_run, 10.0)  # fires the ping at 10 behind the page's back
    _, after = commands.perform_action(tally_run, "poke", {"n": 1}, folded=folded)
    assert after.state == fold_from_scratch(tally_run).state
    assert [source for source, _, _ in after.state.entries][-2:] == ["ping", "poke"]
