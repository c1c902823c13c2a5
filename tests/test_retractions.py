"""Items that go away at their time (apps.kit.retractions): a MicroChat message its sender
deletes, a MicroMail message recalled, a MicroLendar event its organiser cancels, a MicroDin job
closed to applications, a MicroHub pull request someone else closes. Pure reducers and the
grading database, no server."""

from __future__ import annotations

import sqlite3

import pytest

from apps.microchat import screens as chat_screens
from apps.microchat import state as chats
from apps.microchat.environment import MICROCHAT
from apps.microdin.environment import MICRODIN
from apps.microhub.environment import MICROHUB
from apps.microlendar import state as agenda_state
from apps.microlendar.environment import MICROLENDAR
from apps.micromail import state as mailbox
from apps.micromail.environment import MICROMAIL
from events.registry import ActionRejected
from tests.microchat.workspace import CAST as CHAT
from tests.microchat.workspace import PAYMENTS_DOWN
from tests.microdin.cast import CAST as DIN
from tests.microhub.cast import CAST as HUB
from tests.microlendar.cast import CAST as LENDAR
from tests.micromail.cast import CAST as MAIL


def window_of(environment, state, table: str, item_id: str) -> tuple:
    conn = sqlite3.connect(":memory:")
    environment.materialize(state, 500.0, conn)
    return conn.execute(
        f"SELECT appeared_at, gone_at FROM {table} WHERE id = ?", (item_id,)
    ).fetchone()


def test_a_deleted_chat_message_keeps_its_place_shows_teams_notice_and_leaves_the_counts():
    chat = CHAT.arrive(CHAT.preloaded(), "new_message", {"message_id": PAYMENTS_DOWN}, at=120.0)
    assert chats.urgent_count(chat) == 1
    chat = CHAT.arrive(chat, "unsend_message", {"message_id": PAYMENTS_DOWN}, at=180.0)
    assert chat.messages[PAYMENTS_DOWN].gone_at == 180.0
    assert chats.urgent_count(chat) == 0 and chats.unread_count(chat) == 0
    last = chat_screens.last_message(chat, "direct-gabriel")
    assert chat_screens.preview_of(last) == "This message has been deleted."
    assert window_of(MICROCHAT, chat, "messages", PAYMENTS_DOWN) == (120.0, 180.0)
    # Present the whole time: NULL until it goes.
    assert window_of(MICROCHAT, chat, "messages", "dm-gabriel-01")[1] is None
    with pytest.raises(ActionRejected, match="no message"):
        CHAT.act(chat, "react", {"message_id": PAYMENTS_DOWN, "reaction": "like"})


def test_the_first_retraction_counts_and_one_of_an_item_not_there_changes_nothing():
    chat = CHAT.arrive(CHAT.preloaded(), "new_message", {"message_id": PAYMENTS_DOWN}, at=120.0)
    once = CHAT.arrive(chat, "unsend_message", {"message_id": PAYMENTS_DOWN}, at=180.0)
    assert CHAT.arrive(once, "unsend_message", {"message_id": PAYMENTS_DOWN}, at=240.0) == once
    assert CHAT.arrive(chat, "unsend_message", {"message_id": "no-such"}, at=240.0) == chat


def test_a_recalled_mail_leaves_every_folder_and_count_but_stays_in_the_grading_database():
    mail = MAIL.arrive(MAIL.preloaded(), "new_email", {"email_id": "late-report"}, at=120.0)
    unread = mailbox.unread_count(mail)
    mail = MAIL.arrive(mail, "recall_email", {"email_id": "late-report"}, at=200.0)
    assert "late-report" not in mailbox.in_folder(mail, None)
    assert mailbox.unread_count(mail) == unread - 1
    assert mailbox.folder_badges(mail)["inbox"] == unread - 1
    assert window_of(MICROMAIL, mail, "emails", "late-report") == (120.0, 200.0)
    with pytest.raises(ActionRejected, match="no email"):
        MAIL.act(mail, "mark_read", {"email_id": "late-report"})


def test_a_cancelled_invitation_leaves_the_calendar_and_its_counts_and_cannot_be_touched():
    agenda = LENDAR.arrive(LENDAR.preloaded(), "new_event", {"event_id": "td-05"}, at=60.0)
    assert agenda_state.new_invitations(agenda)[0].id == "td-05"
    before = agenda_state.event_count(agenda)
    agenda = LENDAR.arrive(agenda, "cancel_event", {"event_id": "td-05"}, at=150.0)
    assert agenda.cancelled("td-05") and not agenda.has_event("td-05")
    assert agenda_state.event_count(agenda) == before - 1
    assert "td-05" not in [e.id for e in agenda_state.new_invitations(agenda)]
    assert window_of(MICROLENDAR, agenda, "events", "td-05") == (60.0, 150.0)
    assert window_of(MICROLENDAR, agenda, "events", "td-01") == (0.0, None)
    with pytest.raises(ActionRejected, match="no event"):
        LENDAR.act(agenda, "delete_event", {"event_id": "td-05"})


def test_a_closed_job_stays_listed_but_an_application_is_refused_saying_it_closed():
    network = DIN.arrive(DIN.preloaded(), "new_job", {"job_id": "job-21"}, at=120.0)
    network = DIN.arrive(network, "close_job", {"job_id": "job-21"}, at=300.0)
    assert "job-21" in network.jobs  # LinkedIn keeps a closed posting up, marked closed
    assert window_of(MICRODIN, network, "jobs", "job-21") == (120.0, 300.0)
    with pytest.raises(ActionRejected, match="no longer accepting applications") as refused:
        DIN.act(network, "apply_job", {"job_id": "job-21"})
    assert refused.value.status == 409


def test_a_pull_request_someone_else_closed_shows_closed_and_takes_no_comment_or_merge():
    hub = HUB.arrive(HUB.preloaded(), "new_pull_request", {"pr_id": "pr5"}, at=150.0)
    hub = HUB.arrive(hub, "close_pull_request", {"pr_id": "pr5"}, at=260.0)
    assert hub.pr_state("pr5") == "closed"
    assert window_of(MICROHUB, hub, "prs", "pr5") == (150.0, 260.0)
    for action, payload in (("comment_pr", {"body": "Reviewing today."}), ("merge_pr", {})):
        with pytest.raises(ActionRejected, match="no pull request"):
            HUB.act(hub, action, {"pr_id": "pr5", **payload})


def test_the_users_own_merge_stands_when_someone_closes_the_pull_request_afterwards():
    hub = HUB.arrive(HUB.preloaded(), "new_pull_request", {"pr_id": "pr5"}, at=150.0)
    hub = HUB.act(hub, "merge_pr", {"pr_id": "pr5"}, at=200.0)
    hub = HUB.arrive(hub, "close_pull_request", {"pr_id": "pr5"}, at=260.0)
    assert hub.pr_state("pr5") == "merged"
