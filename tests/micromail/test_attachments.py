"""Attaching documents in compose, and previewing attachments: reducers, listing, eval tables."""

from __future__ import annotations

import sqlite3

import pytest

from apps.micromail import state as mailbox
from apps.micromail.compose import prefill
from apps.micromail.environment import materialize
from apps.micromail.query import MailboxQuery
from apps.micromail.screens import document_title, mailbox_screen, preview_of
from apps.micromail.state import Attachment
from events.registry import ActionRejected
from tests.micromail.cast import CAST, PRIYA

ROOT = "/r/t/micromail/"


def in_folder(mail, folder: str) -> list:
    return [mail.emails[i] for i, s in mail.states.items() if s.folder == folder]


def test_the_shelf_holds_the_documents_of_mail_in_the_mailbox_newest_first():
    mail = CAST.arrive(CAST.preloaded(), "new_email", {"email_id": "late-report"})
    assert [a.id for a in mailbox.attachment_shelf(mail)] == [
        "att-report",
        "att-budget",
        "att-notes",
    ]


def test_mail_not_arrived_yet_puts_nothing_on_the_shelf():
    assert "att-report" not in {a.id for a in mailbox.attachment_shelf(CAST.preloaded())}


def test_sent_mail_carries_its_attachments():
    mail = CAST.act(
        CAST.preloaded(), "send", {"to": [PRIYA], "attachments": ["att-notes", "att-budget"]}
    )
    (sent,) = in_folder(mail, "sent")
    assert [a.name for a in sent.attachments] == ["budget-notes.pdf", "budget-q3.xlsx"]
    assert sent.has_attachment is True


def test_an_attachment_listed_twice_is_attached_once():
    mail = CAST.act(
        CAST.preloaded(), "send", {"to": [PRIYA], "attachments": ["att-notes", "att-notes"]}
    )
    (sent,) = in_folder(mail, "sent")
    assert [a.id for a in sent.attachments] == ["att-notes"]


def test_a_document_not_in_the_mailbox_is_a_404_naming_it():
    with pytest.raises(ActionRejected, match="'att-report'") as refused:
        CAST.act(CAST.preloaded(), "send", {"to": [PRIYA], "attachments": ["att-report"]})
    assert refused.value.status == 404


def test_a_draft_with_only_an_attachment_is_worth_saving():
    mail = CAST.act(CAST.preloaded(), "save_draft", {"attachments": ["att-budget"]})
    (draft,) = in_folder(mail, "drafts")
    assert [a.id for a in draft.attachments] == ["att-budget"]


def test_sending_a_draft_keeps_its_attachments_though_the_draft_goes():
    mail = CAST.act(
        CAST.preloaded(), "save_draft", {"subject": "Plan", "attachments": ["att-budget"]}
    )
    (draft,) = in_folder(mail, "drafts")
    mail = CAST.act(
        mail,
        "send",
        {"to": [PRIYA], "subject": "Plan", "attachments": ["att-budget"], "draft_id": draft.id},
    )
    (sent,) = in_folder(mail, "sent")
    assert draft.id not in mail.emails and [a.id for a in sent.attachments] == ["att-budget"]


def test_the_eval_tables_see_what_was_sent_attached():
    mail = CAST.act(CAST.preloaded(), "send", {"to": [PRIYA], "attachments": ["att-notes"]})
    (sent,) = in_folder(mail, "sent")
    conn = sqlite3.connect(":memory:")
    materialize(mail, 0.0, conn)
    row = conn.execute(
        "SELECT hasAttachment, attachment_name FROM emails WHERE id = ?", (sent.id,)
    ).fetchone()
    assert row == (1, "budget-notes.pdf")
    assert mailbox.attachment_count(mail) == mailbox.attachment_count(CAST.preloaded()) + 1


def test_a_forward_carries_the_messages_attachments_and_a_reply_does_not():
    mail = CAST.preloaded()
    assert prefill(mail, "forward", "budget-review").attachments == ("att-budget", "att-notes")
    assert prefill(mail, "reply", "budget-review").attachments == ()


def test_editing_a_draft_keeps_its_attachments():
    mail = CAST.act(
        CAST.preloaded(), "save_draft", {"subject": "Plan", "attachments": ["att-budget"]}
    )
    (draft,) = in_folder(mail, "drafts")
    assert prefill(mail, "draft", draft.id).attachments == ("att-budget",)


@pytest.mark.parametrize(
    ("name", "kind", "subject"),
    [
        ("budget-q3.xlsx", "picture", "chart"),
        ("routes.csv", "picture", "chart"),
        ("service-dependency-map.png", "picture", "screenshot"),
        ("board-deck.pptx", "picture", "whiteboard"),
        ("budget-notes.pdf", "document", ""),
        ("msa-redlines.docx", "document", ""),
        ("concepts.zip", "none", ""),
    ],
)
def test_a_preview_follows_the_file_type(name, kind, subject):
    email = CAST.preloaded().emails["budget-review"]
    preview = preview_of(email, Attachment("a", name, "1 KB"), "close")
    assert (preview.kind, preview.subject) == (kind, subject)


def test_a_document_preview_shows_the_text_it_came_with():
    email = CAST.preloaded().emails["budget-review"]
    preview = preview_of(email, email.attachments[1], "close")
    assert preview.title == "Budget notes"
    assert preview.lines and all(line in email.body for line in preview.lines)


def test_document_titles_read_like_titles():
    assert document_title("board-deck_finance-draft.pptx") == "Board deck finance draft"


def test_the_preview_screen_opens_over_its_message_and_closes_back_to_it():
    query = MailboxQuery(email="budget-review", preview="att-notes")
    screen = mailbox_screen(CAST.preloaded(), query, ROOT)
    assert screen.preview.attachment.name == "budget-notes.pdf"
    assert screen.preview.close_url == ROOT + "?folder=inbox&email=budget-review"
    assert [link.url for link in screen.opened.attachments] == [
        ROOT + "?folder=inbox&email=budget-review&preview=att-budget",
        ROOT + "?folder=inbox&email=budget-review&preview=att-notes",
    ]


def test_opening_another_row_leaves_the_preview():
    query = MailboxQuery(email="budget-review", preview="att-notes")
    assert query.opening("team-lunch") == "?folder=inbox&email=team-lunch"


def test_a_document_leaves_out_the_letters_greeting_and_signature():
    from apps.micromail.screens import document_lines

    body = "Hi Sunita,\n\nThe plan is attached.\nStorage is the driver.\n\nTobias"
    assert document_lines(body) == ("The plan is attached.", "Storage is the driver.")
