"""The standard "verify projection" test: applying events one by one equals folding from scratch."""

from __future__ import annotations

import pytest

from events import lifecycle
from events.commands import perform_action
from events.projection import clear_cache, fold_from_scratch, logged_events, state_at
from tests.micromail.cast import DANA, PRIYA

pytestmark = pytest.mark.django_db

SESSION = [
    ("open_email", {"email_id": "budget-review"}),
    ("flag", {"email_id": "budget-review"}),
    ("pin", {"email_id": "vendor-quote"}),
    ("move", {"email_id": "prize-scam", "folder": "inbox"}),
    ("save_draft", {"to": [PRIYA], "subject": "Draft"}),
    ("send", {"to": [PRIYA], "bcc": [DANA], "subject": "Re: Q3 budget review", "body": "Done."}),
    ("delete", {"email_id": "team-lunch"}),
    ("delete", {"email_id": "team-lunch"}),
    ("mark_unread", {"email_id": "budget-review"}),
]


def play(run) -> None:
    for name, payload in SESSION[:5]:
        perform_action(run, name, payload)
        state_at(run)  # keep the incremental cache warm between events
    lifecycle.advance(run, 130)  # late-report arrives between the agent's actions
    state_at(run)
    for name, payload in SESSION[5:]:
        perform_action(run, name, payload)
        state_at(run)


def test_the_incremental_state_equals_a_fold_from_scratch(mail_run):
    play(mail_run)
    incremental = state_at(mail_run)
    from_scratch = fold_from_scratch(mail_run).state
    assert incremental == from_scratch
    assert "late-report" in from_scratch.emails and "team-lunch" not in from_scratch.emails


def test_every_past_state_equals_a_fold_of_its_prefix(mail_run):
    play(mail_run)
    for event in logged_events(mail_run.pk):
        clear_cache()
        assert state_at(mail_run, event.seq) == fold_from_scratch(mail_run, event.seq).state


def test_applying_each_event_to_the_previous_state_equals_folding_the_prefix(mail_run):
    from apps.micromail.environment import MICROMAIL
    from events.projection import initial_state

    play(mail_run)
    state = initial_state(mail_run)
    for event in logged_events(mail_run.pk):
        state = MICROMAIL.apply(state, event)
        assert state == fold_from_scratch(mail_run, event.seq).state
