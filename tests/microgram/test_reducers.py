"""MicroGram's reducers and actions on the cast: what each event and action does to the state,
and what the evaluation tables then hold."""

from __future__ import annotations

import json
import sqlite3

import pytest

from apps.kit.feeds import likes_now
from apps.microgram import screens
from apps.microgram.environment import MICROGRAM
from apps.microgram.state import unread_activity_count, unread_in
from events.registry import ActionRejected
from tests.microgram.cast import (
    ARRIVES_AT,
    CAST,
    DESK,
    LATE_STORY,
    MARCO,
    MARKET,
    OWN_POST,
    SGRANT,
    STORIES,
    TRAY,
)


def tables(gram, sql: str) -> list[tuple]:
    conn = sqlite3.connect(":memory:")
    MICROGRAM.materialize(gram, 0.0, conn)
    return conn.execute(sql).fetchall()


def test_the_preload_delivers_posts_stories_threads_and_activity_with_catalog_flags():
    gram = CAST.preloaded()
    assert list(gram.posts) == [OWN_POST, MARKET]
    assert set(gram.stories) == set(STORIES) and not gram.viewed_stories
    assert unread_in(gram, "dm-maya") == 0 and unread_in(gram, "dm-tobias") == 2
    assert gram.read_activity["act-01"] and unread_activity_count(gram) == 1
    assert MICROGRAM.measure_baselines(gram, 0.0)["post_count"] == 2


def test_preload_extras_apply_only_to_loaded_items():
    gram = CAST.preloaded(
        liked_post_ids=[MARKET, DESK], viewed_story_ids=["story-nobody"], followed_user_ids=[MARCO]
    )
    assert gram.post_states[MARKET].is_liked and DESK not in gram.post_states
    assert not gram.viewed_stories and gram.followed == (MARCO,)


def test_a_new_post_arrives_on_top_with_its_comments_and_redelivery_changes_nothing():
    gram = CAST.arrive(CAST.preloaded(), "new_post", {"post_id": DESK})
    assert screens.feed(gram)[0].post.id == DESK
    assert gram.posts[DESK].posted_at == ARRIVES_AT
    again = CAST.arrive(
        CAST.act(gram, "like_post", {"post_id": DESK}), "new_post", {"post_id": DESK}
    )
    assert again.post_states[DESK].is_liked
    rows = tables(gram, f"SELECT COUNT(*) FROM comments WHERE post_id = '{DESK}'")
    assert rows == [(5,)]


def test_liking_counts_once_and_unliking_takes_it_back():
    gram = CAST.preloaded()
    before = gram.posts[MARKET].likes
    liked = CAST.act(gram, "like_post", {"post_id": MARKET})
    assert likes_now(liked, MARKET) == before + 1
    assert tables(liked, f"SELECT likes FROM posts WHERE id = '{MARKET}'") == [(before + 1,)]
    assert tables(liked, "SELECT isLiked FROM post_states WHERE isLiked = 1") == [(1,)]
    assert likes_now(CAST.act(liked, "unlike_post", {"post_id": MARKET}), MARKET) == before


def test_actions_on_items_that_have_not_arrived_are_404():
    with pytest.raises(ActionRejected) as refused:
        CAST.act(CAST.preloaded(), "like_post", {"post_id": DESK})
    assert refused.value.status == 404
    with pytest.raises(ActionRejected):
        CAST.act(
            CAST.preloaded(), "follow_user", {"user_id": "user046"}
        )  # not seen on MicroGram yet


def test_saving_commenting_and_viewing_fill_the_original_columns():
    gram = CAST.act(CAST.preloaded(), "save_post", {"post_id": MARKET})
    gram = CAST.act(gram, "comment_post", {"post_id": MARKET, "text": "  Those tomatoes!  "})
    gram = CAST.act(gram, "view_post", {"post_id": MARKET})
    assert tables(
        gram, "SELECT isSaved, isViewed FROM post_states WHERE post_id = 'post-market-haul'"
    ) == [(1, 1)]
    assert tables(gram, "SELECT post_id, text FROM user_created_comments") == [
        (MARKET, "Those tomatoes!")
    ]
    authors = tables(gram, f"SELECT authorId FROM comments WHERE post_id = '{MARKET}'")
    assert ("user000",) in authors and len(authors) == 3
    with pytest.raises(ActionRejected):
        CAST.act(gram, "comment_post", {"post_id": MARKET, "text": "   "})


def test_watching_a_story_greys_its_ring_and_moves_it_behind_the_unwatched():
    gram = CAST.act(CAST.preloaded(), "view_story", {"story_id": STORIES[0]})
    bar = screens.story_bar(gram)
    assert [b.story.id for b in bar][-1] == STORIES[0] and bar[-1].viewed
    assert tables(gram, "SELECT story_id FROM story_states WHERE isViewed = 1") == [(STORIES[0],)]


def test_the_viewers_arrows_skip_an_expired_story_even_the_open_one_and_reach_a_new_one():
    oldest, middle = STORIES
    gram = CAST.preloaded(story_ids=TRAY)
    assert screens.story_neighbours(gram, SGRANT) == (None, middle)
    gram = CAST.arrive(gram, "expire_story", {"story_id": middle}, at=30.0)
    gram = CAST.arrive(gram, "new_story", {"story_id": LATE_STORY}, at=60.0)
    assert screens.story_neighbours(gram, SGRANT) == (LATE_STORY, oldest)
    # Its own viewer, open when it expired, says so and still steps on past it.
    assert screens.story_neighbours(gram, middle) == (SGRANT, oldest)


def test_a_thread_arrives_whole_its_data_searchable_and_reading_it_clears_unread():
    gram = CAST.arrive(CAST.preloaded(), "new_message", {"message_id": "dm-rosa"})
    assert unread_in(gram, "dm-rosa") == 3
    (data,) = tables(gram, "SELECT data FROM messages WHERE data LIKE '%mockup%'")[0]
    assert json.loads(data)["messages"][1]["senderName"] == "Rosa Delgado"
    assert screens.inbox(gram)[0].preview == "Would love your eyes on it before Thursday"
    read = CAST.act(gram, "read_conversation", {"conversation_id": "dm-rosa"})
    assert tables(read, "SELECT COUNT(*) FROM message_states WHERE isRead = 0") == [
        (2,)
    ]  # Tobias's


def test_sending_a_dm_shows_in_the_thread_but_never_in_messages_data():
    gram = CAST.act(
        CAST.preloaded(), "send_message", {"conversation_id": "dm-tobias", "text": "mockup soon"}
    )
    assert unread_in(gram, "dm-tobias") == 0
    assert screens.thread(gram, "dm-tobias")[-1].text == "mockup soon"
    assert screens.inbox(gram)[0].preview == "You: mockup soon"
    assert tables(gram, "SELECT COUNT(*) FROM messages WHERE data LIKE '%mockup%'") == [(0,)]
    assert tables(gram, "SELECT text FROM sent_messages") == [("mockup soon",)]


def test_following_and_reading_activity():
    before = CAST.preloaded()
    gram = CAST.act(before, "follow_user", {"user_id": MARCO})
    assert tables(gram, "SELECT user_id FROM followed_users") == [(MARCO,)]
    assert screens.profile(gram, MARCO, "posts").followers == (
        screens.profile(before, MARCO, "posts").followers + 1
    )
    assert screens.profile(gram, "user000", "posts").following == 313
    marco_follow = next(r for r in screens.activity(gram) if r.item.id == "act-10")
    assert marco_follow.unread and marco_follow.follows_back
    gram = CAST.act(gram, "mark_activity_read", {"activity_id": "act-10"})
    assert unread_activity_count(gram) == 0
    assert tables(gram, "SELECT COUNT(*) FROM activity_states WHERE isRead = 1") == [(2,)]
    assert CAST.act(gram, "unfollow_user", {"user_id": MARCO}).followed == ()


def test_sharing_a_post_sends_it_into_the_thread():
    gram = CAST.act(
        CAST.preloaded(), "share_post", {"post_id": MARKET, "conversation_id": "dm-maya"}
    )
    last = screens.thread(gram, "dm-maya")[-1]
    assert last.mine and last.post.id == MARKET and last.text == ""
    assert screens.inbox(gram)[0].preview == "You sent a post"
    with pytest.raises(ActionRejected):
        CAST.act(gram, "share_post", {"post_id": DESK, "conversation_id": "dm-maya"})


def test_a_new_conversation_needs_a_follow_and_is_opened_only_once():
    gram = CAST.preloaded()
    with pytest.raises(ActionRejected, match="someone you follow"):
        CAST.act(gram, "start_conversation", {"user_id": MARCO})
    gram = CAST.act(gram, "follow_user", {"user_id": MARCO})
    started = CAST.act(gram, "start_conversation", {"user_id": MARCO})
    (thread,) = [c for c in started.conversations.values() if c.other.id == MARCO]
    assert screens.inbox(started)[0].preview == "Say hi"
    again = MICROGRAM.actions["start_conversation"].decide(started, {"user_id": MARCO})
    assert again["conversation_id"] == thread.id
    maya = MICROGRAM.actions["start_conversation"].decide(gram, {"user_id": "user001"})
    assert maya["conversation_id"] == "dm-maya"  # an existing thread needs no follow
