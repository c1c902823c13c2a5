"""Scenario events: preload_emails and new_email, and the baselines captured by a preload."""

from __future__ import annotations

from apps.micromail.environment import MICROMAIL, PRELOAD_AGE_S
from tests.kit import scenario_event
from tests.micromail.cast import CAST, PRELOADED, SELF_EMAIL


def test_preload_with_a_wildcard_loads_the_whole_emails_table():
    mail = CAST.preloaded(email_ids=["*"])
    assert list(mail.emails) == [*PRELOADED, "late-report"]


def test_preload_keeps_the_catalog_read_state():
    mail = CAST.preloaded()
    assert mail.states["team-lunch"].is_read is True
    assert mail.states["budget-review"].is_read is False


def test_preloaded_mail_arrived_five_minutes_before_the_event():
    mail = CAST.preloaded()
    assert {e.arrived_at for e in mail.emails.values()} == {-PRELOAD_AGE_S}


def test_folder_comes_from_the_catalog_and_defaults_to_inbox():
    mail = CAST.preloaded()
    assert mail.folder_of("prize-scam") == "junk"
    assert mail.folder_of("old-archive") == "archive"
    assert mail.folder_of("budget-review") == "inbox"


def test_new_email_arrives_unread_at_the_event_time():
    mail = CAST.arrive(CAST.preloaded(), "new_email", {"email_id": "late-report"})
    assert mail.states["late-report"].is_read is False
    assert mail.emails["late-report"].arrived_at == 120.0


def test_new_mail_is_unread_even_when_the_catalog_says_read():
    mail = CAST.arrive(CAST.fresh(), "new_email", {"email_id": "team-lunch"}, at=5.0)
    assert mail.states["team-lunch"].is_read is False


def test_sender_is_resolved_from_the_user_catalog():
    email = CAST.preloaded().emails["budget-review"]
    assert (email.sender_name, email.sender_email) == ("Priya Nair", "priya.nair@micromail.test")


def test_an_unknown_sender_becomes_unknown_sender():
    email = CAST.preloaded().emails["prize-scam"]
    assert (email.sender_name, email.sender_email) == ("Unknown Sender", "")


def test_recipients_default_to_the_self_user():
    assert CAST.preloaded().emails["team-lunch"].to == (SELF_EMAIL,)


def test_every_attachment_is_kept():
    email = CAST.preloaded().emails["budget-review"]
    assert [a.name for a in email.attachments] == ["budget-q3.xlsx", "budget-notes.pdf"]


def test_delivering_an_id_twice_keeps_one_row_and_what_the_user_did():
    mail = CAST.preloaded()
    mail = CAST.arrive(mail, "new_email", {"email_id": "team-lunch"}, at=50.0)
    assert list(mail.emails).count("team-lunch") == 1
    assert mail.states["team-lunch"].is_read is True
    assert mail.emails["team-lunch"].arrived_at == -PRELOAD_AGE_S


def test_an_id_missing_from_the_catalog_is_skipped():
    mail = CAST.arrive(CAST.preloaded(), "new_email", {"email_id": "no-such-email"})
    assert "no-such-email" not in mail.emails


PRELOAD = scenario_event("preload_emails", {"email_ids": PRELOADED})


def test_baselines_are_measured_right_after_the_preload():
    _, baselines = MICROMAIL.fold(CAST.fresh(), [PRELOAD])
    assert dict(baselines) == {
        "unread_count": 2,  # budget-review, vendor-quote (team-lunch is read, prize-scam is junk)
        "junk_count": 1,
        "attachment_count": 1,
        "external_count": 1,  # vendor-quote; prize-scam is external but in junk
        "inbox_count": 3,
        "urgent_count": 1,
        "mention_count": 1,
        "cc_count": 1,
    }


def test_new_mail_does_not_move_the_baselines():
    late = scenario_event("new_email", {"email_id": "late-report"}, at=120.0, seq=2)
    assert (
        MICROMAIL.fold(CAST.fresh(), [PRELOAD, late])[1]
        == MICROMAIL.fold(CAST.fresh(), [PRELOAD])[1]
    )


def test_without_a_preload_there_are_no_baselines():
    late = scenario_event("new_email", {"email_id": "late-report"})
    assert dict(MICROMAIL.fold(CAST.fresh(), [late])[1]) == {}


def test_unknown_scenario_event_types_are_ignored():
    mail = CAST.preloaded()
    assert MICROMAIL.apply(mail, scenario_event("noop", {})) == mail
