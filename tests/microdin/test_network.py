"""Reducers and actions of MicroDin, on the cast (no database)."""

from __future__ import annotations

import sqlite3

import pytest

from apps.kit.feeds import likes_now
from apps.microdin import state as net
from apps.microdin.environment import MICRODIN
from events.registry import ActionRejected
from tests.microdin.cast import CAST, KUBERNETES_JOB, ME


def tables(network) -> sqlite3.Connection:
    conn = sqlite3.connect(":memory:")
    MICRODIN.materialize(network, 0.0, conn)
    return conn


def test_the_preload_keeps_catalog_read_flags_and_statuses():
    network = CAST.preloaded()
    assert net.pending_connection_count(network) == 2
    assert net.unread_notification_count(network) == 1  # notif-11 is read in the catalog
    assert net.unread_in(network, "conv-02") == 2
    assert "msg-02-later" not in network.messages  # arrives by its own event
    assert network.me.id == ME and network.me.company.name == "MyMicro Inc."


def test_a_new_job_arrives_newest_first_and_not_applied():
    network = CAST.arrive(CAST.preloaded(), "new_job", {"job_id": KUBERNETES_JOB})
    assert net.newest_first(network.jobs.values(), "posted_at")[0].id == KUBERNETES_JOB
    assert network.job_states[KUBERNETES_JOB].is_applied is False


def test_a_new_message_arrives_unread_in_its_thread():
    network = CAST.act(CAST.preloaded(), "open_conversation", {"conversation_id": "conv-02"})
    assert net.unread_in(network, "conv-02") == 0
    network = CAST.arrive(network, "new_message", {"message_id": "msg-02-later"})
    assert net.unread_in(network, "conv-02") == 1
    assert net.conversation_messages(network, "conv-02")[-1].id == "msg-02-later"


def test_delivering_an_item_twice_changes_nothing():
    network = CAST.act(CAST.preloaded(), "like_post", {"post_id": "post-01"})
    again = CAST.arrive(network, "new_post", {"post_id": "post-01"})
    assert again == network


def test_liking_moves_the_count_by_one_and_unliking_restores_it():
    before = CAST.preloaded()
    liked = CAST.act(before, "like_post", {"post_id": "post-01"})
    assert likes_now(liked, "post-01") == likes_now(before, "post-01") + 1
    row = (
        tables(liked)
        .execute(
            "SELECT p.likes, s.isLiked FROM posts p JOIN post_states s ON s.post_id = p.id WHERE p.id = 'post-01'"
        )
        .fetchone()
    )
    assert row == (likes_now(before, "post-01") + 1, 1)
    assert CAST.act(liked, "unlike_post", {"post_id": "post-01"}) == before


def test_a_comment_is_added_under_the_post_by_the_self_user():
    network = CAST.act(
        CAST.preloaded(), "comment_post", {"post_id": "post-01", "text": "Congratulations!"}
    )
    last = net.all_comments(network, "post-01")[-1]
    assert (last.author.id, last.text) == (ME, "Congratulations!")


def test_an_empty_comment_or_message_is_refused_naming_the_field():
    with pytest.raises(ActionRejected, match="'text' is empty"):
        CAST.act(CAST.preloaded(), "comment_post", {"post_id": "post-01", "text": "  "})
    with pytest.raises(ActionRejected, match="'content' is empty"):
        CAST.act(CAST.preloaded(), "send_message", {"conversation_id": "conv-02", "content": ""})


def test_answering_an_invitation_sets_its_status_once():
    network = CAST.act(CAST.preloaded(), "accept_connection", {"connection_id": "conn-01"})
    network = CAST.act(network, "ignore_connection", {"connection_id": "conn-02"})
    statuses = dict(tables(network).execute("SELECT connection_id, status FROM connection_states"))
    assert statuses == {"conn-01": "accepted", "conn-02": "ignored"}
    assert net.connections_count(network) == network.stats.connections + 1
    with pytest.raises(ActionRejected, match="already accepted") as refused:
        CAST.act(network, "ignore_connection", {"connection_id": "conn-01"})
    assert refused.value.status == 409


def test_a_sent_message_is_stored_from_the_self_user_and_reads_the_thread():
    network = CAST.act(
        CAST.preloaded(), "send_message", {"conversation_id": "conv-02", "content": "On it!"}
    )
    assert net.unread_in(network, "conv-02") == 0
    sent = (
        tables(network)
        .execute(
            "SELECT senderId, content FROM messages WHERE conversationId = 'conv-02' AND senderId = ?",
            (ME,),
        )
        .fetchall()
    )
    assert sent == [(ME, "On it!")]


def test_starting_a_conversation_reuses_the_existing_thread_or_makes_one():
    network = CAST.preloaded()
    decided = MICRODIN.actions["start_conversation"].decide(network, {"user_id": "user012"})
    assert decided["conversation_id"] == "conv-02"
    network = CAST.act(network, "start_conversation", {"user_id": "user049"})
    assert any(c.other.id == "user049" for c in network.conversations.values())


def test_applying_is_once_and_unknown_or_future_jobs_are_404():
    network = CAST.arrive(CAST.preloaded(), "new_job", {"job_id": KUBERNETES_JOB})
    with pytest.raises(ActionRejected) as missing:
        CAST.act(CAST.preloaded(), "apply_job", {"job_id": KUBERNETES_JOB})  # not posted yet
    assert missing.value.status == 404
    applied = CAST.act(network, "apply_job", {"job_id": KUBERNETES_JOB})
    assert net.applied_job_count(applied) == 1
    with pytest.raises(ActionRejected, match="already applied"):
        CAST.act(applied, "apply_job", {"job_id": KUBERNETES_JOB})


def test_reading_a_notification_lowers_the_badge():
    network = CAST.act(CAST.preloaded(), "mark_notification_read", {"notification_id": "notif-01"})
    assert net.unread_notification_count(network) == 0


def test_a_profile_section_needs_a_title_or_content():
    network = CAST.act(
        CAST.preloaded(), "add_profile_section", {"type": "certification", "title": "CSPO"}
    )
    assert [(s.type, s.title) for s in network.sections] == [("certification", "CSPO")]
    with pytest.raises(ActionRejected, match="'title'"):
        CAST.act(network, "add_profile_section", {"type": "skill"})


def test_baselines_are_the_originals_counts():
    measured = MICRODIN.measure_baselines(CAST.preloaded(), 0.0)
    assert dict(measured) == {
        "post_count": 2,
        "pending_connection_count": 2,
        "unread_message_count": 2,
        "unread_conversation_count": 1,
        "unread_notification_count": 1,
        "job_count": 2,
        "applied_job_count": 0,
    }
