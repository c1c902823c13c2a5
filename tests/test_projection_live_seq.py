"""`folded_state(run).live_seq` — the last scenario or action event the fold includes — is what
live pages start from. It must be the log's own answer (`apps.kit.live.last_live_seq`) whether the
state was fast-forwarded from a cached fold or folded from scratch, and page views (kind
`view`), which the fold also sees, must never move it."""

from __future__ import annotations

import re

import pytest
from django.db.models import Max
from django.test import Client

from apps.kit.live import LIVE_KINDS, last_live_seq
from events import lifecycle
from events.commands import perform_action, record_view
from events.models import ClockMode, Event, EventKind
from events.projection import clear_cache, folded_state, state_at
from events.store import append_event
from tests.micromail.conftest import mail_run, mail_url  # noqa: F401 — fixtures

pytestmark = pytest.mark.django_db


@pytest.fixture
def tally_run(tally_spec):
    """A tally run on a virtual clock: a ping at 0 (fired at creation), then 10, 30 and 50."""
    return lifecycle.create_run(tally_spec(), clock_mode=ClockMode.VIRTUAL)


def live_seq_upto(run, seq: int) -> int:
    """The last scenario or action event at or before `seq`, asked of the log."""
    found = Event.objects.filter(run=run, kind__in=LIVE_KINDS, seq__lte=seq).aggregate(m=Max("seq"))
    return found["m"] or 0


def last_seq(run) -> int:
    return Event.objects.filter(run=run).aggregate(m=Max("seq"))["m"]


def assert_live_seq_matches_the_log(run) -> None:
    folded = folded_state(run)
    assert folded.seq == last_seq(run)
    assert folded.live_seq == last_live_seq(run.pk)


# A session in which every kind of event lands on the log, interleaved.
STEPS = [
    ("view",),
    ("advance", 10.0),  # lifecycle `advance` + scenario ping
    ("view",),
    ("view",),
    ("poke", 2),
    ("advance", 20.0),  # lifecycle only: nothing is due
    ("view",),
    ("advance", 50.0),  # two pings
    ("poke", 3),
    ("view",),
]


def play(run, step) -> None:
    match step:
        case ("view",):
            record_view(run, "/tally", at=0.0)
        case ("advance", to):
            lifecycle.advance(run, to)
        case ("poke", n):
            perform_action(run, "poke", {"n": n})


def test_a_new_run_tracks_its_preload(tally_run):
    assert last_live_seq(tally_run.pk) > 0
    assert_live_seq_matches_the_log(tally_run)


def test_fast_forwarding_after_each_step_matches_the_log(tally_run):
    folded_state(tally_run)  # warm: every later fold fast-forwards from the previous one
    for step in STEPS:
        play(tally_run, step)
        assert_live_seq_matches_the_log(tally_run)


def test_a_fold_from_scratch_after_each_step_matches_the_log(tally_run):
    for step in STEPS:
        play(tally_run, step)
        clear_cache()
        assert_live_seq_matches_the_log(tally_run)


def test_page_views_move_the_fold_but_not_its_live_seq(tally_run):
    before = folded_state(tally_run)
    for n in range(5):
        record_view(tally_run, f"/tally?page={n}", at=0.0)
    after = folded_state(tally_run)
    assert after.seq == before.seq + 5
    assert after.live_seq == before.live_seq == last_live_seq(tally_run.pk)


def test_a_fast_forward_over_views_only_keeps_the_cached_live_seq(tally_run):
    perform_action(tally_run, "poke", {"n": 1})
    poked = folded_state(tally_run)
    assert poked.live_seq == poked.seq  # the poke is the last event
    record_view(tally_run, "/tally", at=0.0)
    record_view(tally_run, "/tally", at=0.0)
    assert folded_state(tally_run).live_seq == poked.live_seq == last_live_seq(tally_run.pk)


def test_lifecycle_events_do_not_move_it_either(tally_run):
    before = folded_state(tally_run)
    lifecycle.advance(tally_run, 5.0)  # nothing due before the ping at 10
    append_event(tally_run, EventKind.LIFECYCLE, "note", {}, at=5.0)
    after = folded_state(tally_run)
    assert after.seq > before.seq and after.live_seq == before.live_seq
    assert after.live_seq == last_live_seq(tally_run.pk)


def test_the_cache_fast_forwards_from_an_earlier_partial_fold(tally_run):
    for step in STEPS:
        play(tally_run, step)
    middle = last_seq(tally_run) // 2
    clear_cache()
    assert folded_state(tally_run, middle).live_seq == live_seq_upto(tally_run, middle)
    assert_live_seq_matches_the_log(tally_run)  # from the cached fold at `middle`


def test_every_past_position_knows_its_live_seq_forwards_and_backwards(tally_run):
    for step in STEPS:
        play(tally_run, step)
    positions = list(range(last_seq(tally_run) + 1))
    for seq in positions + positions[::-1]:  # forwards: fast-forward; backwards: from scratch
        assert folded_state(tally_run, seq).live_seq == live_seq_upto(tally_run, seq)
    assert_live_seq_matches_the_log(tally_run)


def page_live_seq(browser: Client, url: str) -> int:
    """The position the page's live client starts from (data-seq of #sentinel-live)."""
    html = browser.get(url).content.decode()
    return int(re.search(r'id="sentinel-live"[^>]*data-seq="(\d+)"', html).group(1))


def test_micromail_pages_start_their_live_client_at_the_last_live_event(
    mail_run,  # noqa: F811 — the imported fixtures
    mail_url,  # noqa: F811
):
    browser = Client()
    views_before = Event.objects.filter(run=mail_run, kind=EventKind.VIEW).count()
    for _ in range(3):  # each GET logs a view, which the next page's fold includes
        assert page_live_seq(browser, mail_url()) == last_live_seq(mail_run.pk)
    assert Event.objects.filter(run=mail_run, kind=EventKind.VIEW).count() == views_before + 3
    perform_action(mail_run, "flag", {"email_id": "budget-review"})
    assert page_live_seq(browser, mail_url()) == last_live_seq(mail_run.pk)
    lifecycle.advance(mail_run, 130)  # late-report arrives
    assert page_live_seq(browser, mail_url("?folder=archive")) == last_live_seq(mail_run.pk)
    clear_cache()
    assert page_live_seq(browser, mail_url()) == last_live_seq(mail_run.pk)
    assert_live_seq_matches_the_log(mail_run)


def test_a_page_that_acts_starts_its_live_client_after_its_own_action(
    mail_run,  # noqa: F811 — the imported fixtures
    mail_url,  # noqa: F811
):
    unread = next(i for i, s in state_at(mail_run).states.items() if not s.is_read)
    seq = page_live_seq(Client(), mail_url(f"?folder=inbox&email={unread}"))  # opening marks read
    opened = Event.objects.filter(run=mail_run, kind=EventKind.ACTION, type="open_email").get()
    assert seq == opened.seq == last_live_seq(mail_run.pk)  # nothing left to push back to it
