"""What scenario events and actions do to the chat workspace (pure reducers, no database)."""

from __future__ import annotations

import json
import sqlite3
from dataclasses import replace

import pytest

from apps.microchat import screens
from apps.microchat import state as chats
from apps.microchat.environment import MICROCHAT
from events.registry import ActionRejected
from tests.microchat.workspace import CAST, GABRIEL_FRESH, GABRIEL_HISTORY, NOOR_FILE, PAYMENTS_DOWN


def test_the_first_preload_loads_every_conversation_and_team_and_keeps_catalog_read_state():
    chat = CAST.preloaded(
        message_ids=GABRIEL_HISTORY + GABRIEL_FRESH, call_ids=["call-missed-01", "call-in-01"]
    )
    assert len(chat.conversations) >= 30 and len(chat.teams) == 10
    assert chat.conversations["direct-gabriel"].name == "Gabriel Nwosu"
    assert [chat.read[i] for i in GABRIEL_HISTORY + GABRIEL_FRESH] == [True] * 3 + [False] * 2
    assert chats.missed_call_count(chat) == 1
    assert chat.pinned("direct-maya") and chat.muted("group-platform-oncall")


def test_history_is_stamped_minutes_before_the_preload_and_arrivals_at_their_event():
    chat = CAST.arrive(CAST.preloaded(), "new_message", {"message_id": PAYMENTS_DOWN}, at=120.0)
    assert chat.messages["dm-gabriel-01"].sent_at == -1500 * 60
    assert chat.messages[PAYMENTS_DOWN].sent_at == 120.0
    assert chat.read[PAYMENTS_DOWN] is False and chat.messages[PAYMENTS_DOWN].is_urgent


def test_a_message_delivered_twice_is_one_message_and_keeps_what_the_user_did():
    chat = CAST.arrive(
        CAST.preloaded(message_ids=[]), "new_message", {"message_id": PAYMENTS_DOWN}, at=5.0
    )
    chat = CAST.act(chat, "open_conversation", {"conversation_id": "direct-gabriel"})
    again = CAST.arrive(chat, "new_message", {"message_id": PAYMENTS_DOWN}, at=9.0)
    assert list(again.messages).count(PAYMENTS_DOWN) == 1 and again.read[PAYMENTS_DOWN] is True


def test_opening_reads_what_is_there_and_a_later_arrival_stays_unread_until_opened_again():
    chat = CAST.preloaded(message_ids=GABRIEL_HISTORY + GABRIEL_FRESH)
    chat = CAST.act(chat, "open_conversation", {"conversation_id": "direct-gabriel"})
    assert all(chat.read[i] for i in GABRIEL_FRESH)
    chat = CAST.arrive(chat, "new_message", {"message_id": PAYMENTS_DOWN}, at=30.0)
    assert chat.read[PAYMENTS_DOWN] is False
    assert screens.unread_counts(chat) == {"direct-gabriel": 1}


def test_opening_a_chat_with_nothing_unread_is_not_an_action():
    chat = CAST.preloaded()
    with pytest.raises(ActionRejected, match="nothing unread"):
        CAST.act(chat, "open_conversation", {"conversation_id": "direct-gabriel"})
    with pytest.raises(ActionRejected, match="no conversation"):
        CAST.act(chat, "open_conversation", {"conversation_id": "direct-nobody"})


def test_mark_unread_makes_the_newest_message_from_someone_else_unread():
    chat = CAST.preloaded()
    chat = CAST.act(chat, "mark_unread", {"conversation_id": "direct-gabriel"})
    assert chats.unread_ids(chat) == ["dm-gabriel-03"]


def test_favourite_and_mute_are_set_not_toggled():
    chat = CAST.preloaded(message_ids=[])
    twice = CAST.act(
        CAST.act(chat, "pin", {"conversation_id": "direct-noor"}),
        "pin",
        {"conversation_id": "direct-noor"},
    )
    assert twice.pinned("direct-noor")
    assert not CAST.act(twice, "unpin", {"conversation_id": "direct-noor"}).pinned("direct-noor")
    assert CAST.act(chat, "mute", {"conversation_id": "direct-noor"}).muted("direct-noor")


def test_reactions_are_the_self_users_and_an_empty_reaction_disappears():
    chat = CAST.preloaded(message_ids=["dm-maya-03"])  # Chris already liked it in the catalog
    assert chat.reactions["dm-maya-03"] == (("like", ("user000",)),)
    chat = CAST.act(chat, "react", {"message_id": "dm-maya-03", "reaction": "heart"})
    chat = CAST.act(chat, "unreact", {"message_id": "dm-maya-03", "reaction": "like"})
    assert chat.reactions["dm-maya-03"] == (("heart", ("user000",)),)
    with pytest.raises(ActionRejected, match="'reaction'"):
        CAST.act(chat, "react", {"message_id": "dm-maya-03", "reaction": "thumbsup"})


def test_sending_replying_editing_and_deleting_your_own_message():
    chat = CAST.preloaded()
    chat = CAST.act(
        chat,
        "send_message",
        {"conversation_id": "direct-gabriel", "content": "  On it!  ", "reply_to": "dm-gabriel-03"},
        at=42.0,
    )
    sent = next(m for m in chat.messages.values() if m.sent_in_run)
    assert (sent.content, sent.reply_to, sent.sent_at, chat.read[sent.id]) == (
        "On it!",
        "dm-gabriel-03",
        42.0,
        True,
    )
    chat = CAST.act(chat, "edit_message", {"message_id": sent.id, "content": "On it now"})
    assert chat.messages[sent.id].content == "On it now" and chat.messages[sent.id].edited
    with pytest.raises(ActionRejected, match="only yours"):
        CAST.act(chat, "delete_message", {"message_id": "dm-gabriel-01"})
    assert sent.id not in CAST.act(chat, "delete_message", {"message_id": sent.id}).messages


def test_sending_checks_the_text_and_the_reply():
    chat = CAST.preloaded(message_ids=[*GABRIEL_HISTORY, "dm-maya-01"])
    with pytest.raises(ActionRejected, match="'content' is empty"):
        CAST.act(chat, "send_message", {"conversation_id": "direct-gabriel", "content": "   "})
    with pytest.raises(ActionRejected, match="not in conversation"):
        CAST.act(
            chat,
            "send_message",
            {"conversation_id": "direct-gabriel", "content": "hi", "reply_to": "dm-maya-01"},
        )


def tables(chat) -> sqlite3.Connection:
    conn = sqlite3.connect(":memory:")
    MICROCHAT.materialize(chat, 0.0, conn)
    return conn


def test_the_evaluation_tables_have_the_originals_shape_and_leave_sent_messages_apart():
    chat = CAST.arrive(
        CAST.preloaded(call_ids=["call-missed-01"]),
        "new_message",
        {"message_id": NOOR_FILE},
        at=3.0,
    )
    chat = CAST.act(
        chat,
        "send_message",
        {"conversation_id": "direct-gabriel", "content": "payment processing service is down"},
    )
    conn = tables(chat)
    assert conn.execute(
        "SELECT id, conversationId, senderId, isUrgent, mentionsMe, hasAttachment FROM messages WHERE id = ?",
        (NOOR_FILE,),
    ).fetchone() == (NOOR_FILE, "direct-noor", "user009", 0, 0, 1)
    assert conn.execute(
        "SELECT COUNT(*) FROM messages WHERE content LIKE '%payment processing%'"
    ).fetchone() == (0,)
    assert conn.execute("SELECT COUNT(*) FROM sent_messages").fetchone() == (1,)
    assert conn.execute(
        "SELECT isRead FROM message_states WHERE message_id = ?", (NOOR_FILE,)
    ).fetchone() == (0,)
    assert conn.execute("SELECT callerId, missed, duration FROM calls").fetchone() == (
        "user019",
        1,
        "",
    )
    assert conn.execute(
        "SELECT isPinned, isMuted FROM conversation_states WHERE conversation_id = 'direct-maya'"
    ).fetchone() == (1, 0)
    assert conn.execute("SELECT COUNT(*) FROM teams").fetchone() == (10,)


def test_baselines_are_the_originals_counts():
    chat = CAST.preloaded(
        message_ids=[*GABRIEL_FRESH, "mention-pm-guild-07", "urg-maya-11"],
        call_ids=["call-missed-01", "call-in-01"],
    )
    assert dict(MICROCHAT.measure_baselines(chat, 0.0)) == {
        "unread_count": 4,
        "unread_conversation_count": 3,
        "mention_count": 1,
        "urgent_count": 1,
        "missed_call_count": 1,
        "total_message_count": 4,
    }


def test_the_originals_record_shapes_are_read(tmp_path):
    """camelCase keys, reactions and attachments as JSON strings, emoji reactions, no isRead."""
    (tmp_path / "microchat").mkdir()
    (tmp_path / "users.json").write_text(
        json.dumps(
            [
                {"id": "user000", "name": "Sam Self", "isSelf": True},
                {"id": "user001", "name": "Ada Lane"},
            ]
        )
    )
    records = {
        "conversations": [
            {
                "id": "direct-ada",
                "type": "direct",
                "name": "x",
                "participantIds": ["user000", "user001"],
            }
        ],
        "messages": [
            {
                "id": "m1",
                "senderId": "user001",
                "conversationId": "direct-ada",
                "content": "see file",
                "reactions": json.dumps([{"emoji": "👍", "userIds": ["user001"]}]),
                "attachments": json.dumps([{"name": "plan.pdf", "type": "file", "size": "2 KB"}]),
            },
            {
                "id": "m2",
                "sender_id": "user001",
                "conversation_id": "direct-ada",
                "content": "x",
                "hasAttachment": True,
                "is_read": True,
            },
        ],
        "calls": [
            {
                "id": "c1",
                "name": "Old name",
                "userId": "user001",
                "type": "incoming",
                "duration": "",
                "time": "1 hour ago",
                "missed": True,
            }
        ],
    }
    for table, rows in records.items():
        (tmp_path / "microchat" / f"{table}.jsonl").write_text(
            "\n".join(json.dumps(r) for r in rows)
        )
    chat = replace(CAST, catalog_dir=tmp_path).preloaded(message_ids=["*"], call_ids=["*"])
    assert chat.conversations["direct-ada"].name == "Ada Lane"
    assert chat.reactions["m1"] == (("like", ("user001",)),)
    assert (
        chat.messages["m1"].attachments[0].name == "plan.pdf" and chat.messages["m1"].has_attachment
    )
    assert chat.messages["m2"].attachments[0].name == "Attachment" and chat.read["m2"] is True
    assert chat.calls["c1"].name == "Ada Lane" and chat.calls["c1"].time_text == "1 hour ago"
