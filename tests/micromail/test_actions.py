"""Agent actions: each one's effect, and the requests it rejects."""

from __future__ import annotations

import pytest

from apps.micromail.environment import MICROMAIL
from events.registry import ActionRejected, LoggedEvent
from tests.micromail.cast import CAST, DANA, OMAR, PRIYA, SELF_EMAIL


def test_opening_an_email_marks_it_read():
    assert (
        CAST.act(CAST.preloaded(), "open_email", {"email_id": "budget-review"})
        .states["budget-review"]
        .is_read
    )


def test_mark_unread_then_mark_read():
    mail = CAST.act(CAST.preloaded(), "mark_unread", {"email_id": "team-lunch"})
    assert mail.states["team-lunch"].is_read is False
    assert (
        CAST.act(mail, "mark_read", {"email_id": "team-lunch"}).states["team-lunch"].is_read is True
    )


def test_flag_is_set_not_toggled():
    mail = CAST.act(CAST.preloaded(), "flag", {"email_id": "budget-review"})
    mail = CAST.act(mail, "flag", {"email_id": "budget-review"})
    assert mail.states["budget-review"].is_flagged is True
    assert (
        CAST.act(mail, "unflag", {"email_id": "budget-review"}).states["budget-review"].is_flagged
        is False
    )


def test_pin_and_unpin():
    mail = CAST.act(CAST.preloaded(), "pin", {"email_id": "vendor-quote"})
    assert mail.states["vendor-quote"].is_pinned is True
    assert (
        CAST.act(mail, "unpin", {"email_id": "vendor-quote"}).states["vendor-quote"].is_pinned
        is False
    )


def test_move_changes_the_folder():
    mail = CAST.act(CAST.preloaded(), "move", {"email_id": "budget-review", "folder": "archive"})
    assert mail.folder_of("budget-review") == "archive"


def test_move_to_an_unknown_folder_is_rejected_listing_the_folders():
    with pytest.raises(
        ActionRejected, match="allowed: inbox, sent, drafts, archive, junk, deleted, scheduled"
    ):
        CAST.act(CAST.preloaded(), "move", {"email_id": "budget-review", "folder": "spam"})


@pytest.mark.parametrize("name", ["open_email", "mark_read", "flag", "pin", "delete"])
def test_an_unknown_email_is_a_404(name):
    with pytest.raises(ActionRejected) as raised:
        CAST.act(CAST.preloaded(), name, {"email_id": "late-report"})  # not arrived yet
    assert raised.value.status == 404


def test_delete_moves_to_deleted_items_and_keeps_the_row():
    mail = CAST.act(CAST.preloaded(), "delete", {"email_id": "team-lunch"})
    assert mail.folder_of("team-lunch") == "deleted"


def test_deleting_from_deleted_items_purges():
    mail = CAST.act(CAST.preloaded(), "delete", {"email_id": "team-lunch"})
    mail = CAST.act(mail, "delete", {"email_id": "team-lunch"})
    assert "team-lunch" not in mail.emails and "team-lunch" not in mail.states


def test_deleting_a_draft_purges_it():
    mail = CAST.act(CAST.preloaded(), "save_draft", {"subject": "Half-written"})
    draft_id = next(i for i, s in mail.states.items() if s.folder == "drafts")
    assert draft_id not in CAST.act(mail, "delete", {"email_id": draft_id}).emails


def test_a_purged_email_is_a_404_afterwards():
    mail = CAST.act(
        CAST.act(CAST.preloaded(), "delete", {"email_id": "team-lunch"}),
        "delete",
        {"email_id": "team-lunch"},
    )
    with pytest.raises(ActionRejected) as raised:
        CAST.act(mail, "open_email", {"email_id": "team-lunch"})
    assert raised.value.status == 404


def sent_items(mail):
    return [mail.emails[i] for i, s in mail.states.items() if s.folder == "sent"]


def test_send_puts_a_read_message_from_the_self_user_in_sent_items():
    mail = CAST.act(
        CAST.preloaded(), "send", {"to": [PRIYA], "subject": "Hello", "body": "Hi"}, at=42.0
    )
    (sent,) = sent_items(mail)
    assert (sent.sender_email, sent.to, sent.subject, sent.arrived_at) == (
        SELF_EMAIL,
        (PRIYA,),
        "Hello",
        42.0,
    )
    assert mail.states[sent.id].is_read is True


def test_send_keeps_bcc():
    mail = CAST.act(
        CAST.preloaded(),
        "send",
        {"to": [PRIYA], "cc": [OMAR], "bcc": [DANA], "subject": "s", "body": "b"},
    )
    (sent,) = sent_items(mail)
    assert (sent.cc, sent.bcc) == ((OMAR,), (DANA,))


def test_send_records_its_generated_id_so_replay_reuses_it():
    recorded = MICROMAIL.actions["send"].decide(CAST.preloaded(), {"to": [PRIYA]})
    assert recorded["id"].startswith("sent-")
    event = LoggedEvent(9, 5.0, "action", "send", recorded)
    first, second = (
        MICROMAIL.apply(CAST.preloaded(), event),
        MICROMAIL.apply(CAST.preloaded(), event),
    )
    assert first == second and recorded["id"] in first.emails


def test_send_names_the_bad_address():
    with pytest.raises(ActionRejected, match="'not-an-address' in cc is not a valid email address"):
        CAST.act(CAST.preloaded(), "send", {"to": [PRIYA], "cc": ["not-an-address"]})


def test_send_needs_a_recipient():
    with pytest.raises(ActionRejected, match="at least one recipient"):
        CAST.act(CAST.preloaded(), "send", {"to": [], "subject": "Into the void"})


def test_send_rejects_addresses_that_are_not_strings():
    with pytest.raises(ActionRejected, match=r"payload field 'to\[0\]' must be string, got 42"):
        CAST.act(CAST.preloaded(), "send", {"to": [42]})


def test_null_compose_fields_count_as_left_out():
    mail = CAST.act(CAST.preloaded(), "send", {"to": [PRIYA], "cc": None, "subject": None})
    (sent,) = sent_items(mail)
    assert (sent.cc, sent.subject) == ((), "")


def test_save_draft_creates_a_read_draft():
    mail = CAST.act(CAST.preloaded(), "save_draft", {"to": [PRIYA], "subject": "Plan"})
    (draft_id,) = [i for i, s in mail.states.items() if s.folder == "drafts"]
    assert draft_id.startswith("drafts-") and mail.emails[draft_id].subject == "Plan"


def test_saving_a_draft_again_updates_it_in_place():
    mail = CAST.act(CAST.preloaded(), "save_draft", {"subject": "Plan"})
    (draft_id,) = [i for i, s in mail.states.items() if s.folder == "drafts"]
    mail = CAST.act(mail, "save_draft", {"subject": "Plan v2", "draft_id": draft_id})
    drafts = [i for i, s in mail.states.items() if s.folder == "drafts"]
    assert drafts == [draft_id] and mail.emails[draft_id].subject == "Plan v2"


def test_sending_a_draft_removes_the_draft():
    mail = CAST.act(CAST.preloaded(), "save_draft", {"to": [PRIYA], "subject": "Plan"})
    (draft_id,) = [i for i, s in mail.states.items() if s.folder == "drafts"]
    mail = CAST.act(mail, "send", {"to": [PRIYA], "subject": "Plan", "draft_id": draft_id})
    assert draft_id not in mail.emails and len(sent_items(mail)) == 1


def test_draft_id_must_be_a_draft():
    with pytest.raises(ActionRejected, match="is not a draft"):
        CAST.act(CAST.preloaded(), "send", {"to": [PRIYA], "draft_id": "budget-review"})


def test_an_empty_draft_is_rejected():
    with pytest.raises(ActionRejected, match="nothing to save"):
        CAST.act(CAST.preloaded(), "save_draft", {})


def test_unknown_payload_fields_are_rejected_naming_the_allowed_ones():
    with pytest.raises(ActionRejected, match="allowed: email_id"):
        CAST.act(CAST.preloaded(), "flag", {"email_id": "budget-review", "colour": "red"})


def test_an_action_on_an_email_purged_meanwhile_changes_nothing_on_replay():
    mail = CAST.act(
        CAST.act(CAST.preloaded(), "delete", {"email_id": "team-lunch"}),
        "delete",
        {"email_id": "team-lunch"},
    )
    stale = LoggedEvent(50, 1.0, "action", "flag", {"email_id": "team-lunch"})
    assert MICROMAIL.apply(mail, stale) == mail
