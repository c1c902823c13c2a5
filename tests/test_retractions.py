"""Items that go away at their time (apps.kit.retractions): a MicroChat message its sender
deletes, a MicroMail message recalled, a MicroScholar preprint withdrawn by its authors. Pure reducers and the grading database, no server."""

from __future__ import annotations

import sqlite3

import pytest

from apps.microchat import screens as chat_screens
from apps.microchat import state as chats
from apps.microchat.environment import MICROCHAT
from apps.micromail import state as mailbox
from apps.micromail.environment import MICROMAIL
from apps.microscholar import screens as scholar_screens
from apps.microscholar import state as papers
from apps.microscholar.environment import MICROSCHOLAR
from events.registry import ActionRejected
from tests.microchat.workspace import CAST as CHAT
from tests.microchat.workspace import PAYMENTS_DOWN
from tests.micromail.cast import CAST as MAIL
from tests.microscholar import cast as scholar_cast
from tests.microscholar.cast import BATCHING, TARGET
from tests.microscholar.cast import CAST as SCHOLAR


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


def test_a_withdrawn_preprint_leaves_results_profiles_and_library_and_says_so_on_its_page():
    scholar = scholar_cast.preloaded(["paper-021", BATCHING], saved=[BATCHING])
    scholar = SCHOLAR.arrive(scholar, "new_paper", {"paper_id": TARGET}, at=120.0)
    scholar = SCHOLAR.act(scholar, "save", {"paper_id": TARGET}, at=150.0)
    assert papers.saved_paper_count(scholar) == 2 and papers.paper_count(scholar) == 3
    assert TARGET in scholar_screens.matching(scholar, "delegation", None, None, "relevance")
    scholar = SCHOLAR.arrive(scholar, "withdraw_paper", {"paper_id": TARGET}, at=200.0)
    assert TARGET not in scholar_screens.recommended(scholar)
    assert TARGET not in scholar_screens.matching(scholar, "delegation", None, None, "relevance")
    assert scholar_screens.library(scholar) == (BATCHING,)
    assert papers.saved_paper_count(scholar) == 1 and papers.paper_count(scholar) == 2
    # Graded as it was: saved while it was there, with its window.
    assert window_of(MICROSCHOLAR, scholar, "papers", TARGET) == (120.0, 200.0)
    with pytest.raises(ActionRejected, match="no paper"):
        SCHOLAR.act(scholar, "cite", {"paper_id": TARGET}, at=210.0)
    with pytest.raises(ActionRejected, match="no paper"):
        SCHOLAR.act(scholar, "unsave", {"paper_id": TARGET}, at=210.0)
