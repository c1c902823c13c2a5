"""The evaluation tables: upstream names, columns and encodings, so eval_sql runs unchanged."""

from __future__ import annotations

import sqlite3

from apps.micromail.environment import materialize
from tests.micromail.cast import CAST, PRIYA


def tables(mail) -> sqlite3.Connection:
    conn = sqlite3.connect(":memory:")
    materialize(mail, 0.0, conn)
    return conn


def columns(conn, table: str) -> list[str]:
    return [row[1] for row in conn.execute(f"PRAGMA table_info({table})")]


def test_emails_columns_are_upstreams_then_ours():
    # Upstream's, then when each message was there (apps.kit.retractions: a recall ends it).
    assert columns(tables(CAST.preloaded()), "emails") == [
        "id",
        "subject",
        "sender_name",
        "sender_email",
        "hasAttachment",
        "isExternal",
        "importance",
        "mentionsMe",
        "isCC",
        "body",
        "attachment_name",
        "appeared_at",
        "gone_at",
    ]


def test_email_states_columns_are_upstreams():
    assert columns(tables(CAST.preloaded()), "email_states") == [
        "email_id",
        "isRead",
        "isFlagged",
        "isPinned",
        "folder",
    ]


def test_booleans_are_integers_zero_or_one():
    sql = (
        "SELECT hasAttachment, isExternal, mentionsMe, isCC, typeof(isCC) "
        "FROM emails WHERE id = 'budget-review'"
    )
    row = tables(CAST.preloaded()).execute(sql).fetchone()
    assert row == (1, 0, 1, 0, "integer")


def test_state_booleans_are_integers_zero_or_one():
    mail = CAST.act(CAST.preloaded(), "flag", {"email_id": "team-lunch"})
    sql = (
        "SELECT isRead, isFlagged, isPinned, folder FROM email_states WHERE email_id = 'team-lunch'"
    )
    row = tables(mail).execute(sql).fetchone()
    assert row == (1, 1, 0, "inbox")


def test_every_attachment_name_is_searchable_with_like():
    conn = tables(CAST.preloaded())
    assert conn.execute(
        "SELECT attachment_name FROM emails WHERE id = 'budget-review'"
    ).fetchone() == ("budget-q3.xlsx, budget-notes.pdf",)
    assert conn.execute(
        "SELECT COUNT(*) FROM emails WHERE attachment_name LIKE '%notes.pdf%'"
    ).fetchone() == (1,)


def test_attachment_name_is_empty_text_when_there_is_none():
    conn = tables(CAST.preloaded())
    assert conn.execute(
        "SELECT attachment_name FROM emails WHERE id = 'team-lunch'"
    ).fetchone() == ("",)


def test_importance_defaults_to_normal():
    conn = tables(CAST.preloaded())
    assert conn.execute("SELECT importance FROM emails WHERE id = 'team-lunch'").fetchone() == (
        "normal",
    )


def test_sent_mail_is_a_row_like_upstream():
    mail = CAST.act(CAST.preloaded(), "send", {"to": [PRIYA], "subject": "Hello"})
    conn = tables(mail)
    sql = (
        "SELECT e.subject, s.folder, s.isRead FROM emails e "
        "JOIN email_states s ON s.email_id = e.id WHERE e.id LIKE 'sent-%'"
    )
    assert conn.execute(sql).fetchall() == [("Hello", "sent", 1)]


def test_a_purged_email_is_gone_from_both_tables():
    mail = CAST.act(
        CAST.act(CAST.preloaded(), "delete", {"email_id": "team-lunch"}),
        "delete",
        {"email_id": "team-lunch"},
    )
    conn = tables(mail)
    assert conn.execute("SELECT COUNT(*) FROM emails WHERE id = 'team-lunch'").fetchone() == (0,)
    assert conn.execute(
        "SELECT COUNT(*) FROM email_states WHERE email_id = 'team-lunch'"
    ).fetchone() == (0,)
