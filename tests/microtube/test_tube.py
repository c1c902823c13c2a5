"""MicroTube's domain: what scenario events and agent actions do to the site, the baselines,
the drifting counts and the evaluation tables (reducers, decisions and materialize, no pages)."""

from __future__ import annotations

import json
import sqlite3
from types import SimpleNamespace

import pytest

from apps.kit.streaming import COUNT_REFRESH_S
from apps.microtube import display, screens
from apps.microtube.environment import MICROTUBE
from apps.microtube.state import comment_count, notification_count, unread_notification_count
from events.registry import ActionRejected
from tests.microtube.cast import CAST, DESK_SETUP, UPLOAD_AT, WALKTHROUGH

act, arrive, preloaded = CAST.act, CAST.arrive, CAST.preloaded


def tables(tube, now: float = 0.0) -> sqlite3.Connection:
    conn = sqlite3.connect(":memory:")
    MICROTUBE.materialize(tube, now, conn)
    return conn


def one(conn: sqlite3.Connection, sql: str):
    return conn.execute(sql).fetchone()[0]


def test_the_preload_loads_the_channels_subscriptions_history_and_the_self_identity():
    tube = preloaded()
    assert list(tube.videos) == [WALKTHROUGH, "vid-pixel-02", "vid-reel-01", "vid-self-01"]
    assert tube.is_subscribed("ch-pixel-forge") and not tube.is_subscribed("ch-reel-talk")
    assert tube.watched == ("vid-self-01",)
    me = tube.channels["ch-self"]
    assert (me.name, me.handle, me.is_self) == ("Chris Taylor", "@ctaylor", True)
    assert tube.comments["cmt-01"].author == "Theo Blackwood"
    assert notification_count(tube) == 2 and unread_notification_count(tube) == 1


def test_baselines_are_the_counts_right_after_the_preload():
    measured = MICROTUBE.measure_baselines(preloaded(), 0.0)
    assert measured == {
        "subscribed_count": 1,
        "liked_count": 0,
        "watched_count": 1,
        "comment_count": 2,
        "notification_count": 2,
        "playlist_count": 0,
        "video_count": 4,
    }


def test_an_upload_brings_its_channel_and_tops_home_and_subscriptions():
    tube = arrive(preloaded(channel_ids=[]), "new_video", {"video_id": "vid-orbit-03"})
    assert "ch-orbit-notes" in tube.channels  # the original left it without a channel
    tube = arrive(tube, "new_video", {"video_id": DESK_SETUP})
    assert [c.video.id for c in screens.home(tube)][:2] == [DESK_SETUP, "vid-orbit-03"]
    assert screens.subscriptions(tube)[0].video.id == DESK_SETUP
    assert "vid-orbit-03" not in [c.video.id for c in screens.subscriptions(tube)]


def test_unknown_ids_and_repeats_change_nothing():
    tube = preloaded()
    assert arrive(tube, "new_video", {"video_id": "vid-nope"}) == tube
    assert arrive(tube, "new_comment", {"comment_id": "cmt-01"}) == tube
    assert arrive(tube, "new_notification", {"notification_id": "notif-01"}) == tube


def test_like_and_dislike_exclude_each_other():
    tube = act(preloaded(), "like_video", {"video_id": WALKTHROUGH})
    assert tube.video_states[WALKTHROUGH].liked
    tube = act(tube, "dislike_video", {"video_id": WALKTHROUGH})
    state = tube.video_states[WALKTHROUGH]
    assert (state.liked, state.disliked) == (False, True)
    tube = act(tube, "undislike_video", {"video_id": WALKTHROUGH})
    assert not tube.video_states[WALKTHROUGH].disliked


def test_a_video_not_uploaded_yet_cannot_be_rated():
    with pytest.raises(ActionRejected) as refused:
        act(preloaded(), "like_video", {"video_id": DESK_SETUP})
    assert refused.value.status == 404 and DESK_SETUP in str(refused.value)


def test_subscribing_moves_the_shown_count_by_one_but_not_the_table():
    tube = preloaded()
    assert tube.own_subscription("ch-reel-talk") == 0
    tube = act(tube, "subscribe", {"channel_id": "ch-reel-talk"})
    tube = act(tube, "subscribe", {"channel_id": "ch-reel-talk"})  # a repeat changes nothing
    assert tube.own_subscription("ch-reel-talk") == 1
    conn = tables(tube)
    assert one(conn, "SELECT subscribers FROM channels WHERE id='ch-reel-talk'") == 1_730_000
    assert one(conn, "SELECT isSubscribed FROM channel_states WHERE channel_id='ch-reel-talk'") == 1
    tube = act(tube, "unsubscribe", {"channel_id": "ch-reel-talk"})
    assert tube.own_subscription("ch-reel-talk") == 0


def test_a_comment_is_the_users_own_and_counts_in_the_comment_baseline():
    tube = act(preloaded(), "post_comment", {"video_id": WALKTHROUGH, "content": "  Great run!  "})
    mine = tube.user_comments["user-cmt-1"]
    assert (mine.content, mine.author, mine.by_self) == ("Great run!", "Chris Taylor", True)
    assert screens.comments(tube, WALKTHROUGH)[0] == mine
    assert comment_count(tube) == 3
    assert one(tables(tube), "SELECT content FROM user_created_comments") == "Great run!"
    with pytest.raises(ActionRejected, match="content"):
        act(tube, "post_comment", {"video_id": WALKTHROUGH, "content": "   "})


def test_notifications_are_read_and_dismissed():
    tube = act(preloaded(), "read_notification", {"notification_id": "notif-01"})
    assert unread_notification_count(tube) == 0
    assert screens.notification_target(tube, "notif-01") == ""  # its channel is not on the site
    assert screens.notification_target(tube, "notif-09") == "channel/ch-self"  # video not yet
    tube = act(tube, "dismiss_notification", {"notification_id": "notif-09"})
    assert [r.notification.id for r in screens.notifications(tube)] == ["notif-01"]
    conn = tables(tube)
    assert one(conn, "SELECT isDismissed FROM notification_states WHERE notification_id='notif-09'")
    assert one(conn, "SELECT COUNT(*) FROM notifications") == 2


def test_playlists_are_created_with_the_video_and_never_hold_it_twice():
    tube = act(preloaded(), "create_playlist", {"name": "Strategy", "video_id": WALKTHROUGH})
    tube = act(tube, "add_to_playlist", {"playlist_id": "pl-user-1", "video_id": WALKTHROUGH})
    tube = act(tube, "add_to_playlist", {"playlist_id": "pl-user-1", "video_id": "vid-pixel-02"})
    assert tube.playlists["pl-user-1"].video_ids == (WALKTHROUGH, "vid-pixel-02")
    data = json.loads(one(tables(tube), "SELECT data FROM user_created_playlists"))
    assert data["video_ids"] == [WALKTHROUGH, "vid-pixel-02"] and data["name"] == "Strategy"
    with pytest.raises(ActionRejected) as refused:
        act(tube, "add_to_playlist", {"playlist_id": "pl-user-9", "video_id": WALKTHROUGH})
    assert refused.value.status == 404


def test_watching_is_recorded_once_and_history_is_latest_first():
    tube = act(preloaded(), "watch_video", {"video_id": WALKTHROUGH})
    tube = act(tube, "watch_video", {"video_id": WALKTHROUGH})
    assert tube.watched == ("vid-self-01", WALKTHROUGH)
    assert [c.video.id for c in screens.history(tube)] == [WALKTHROUGH, "vid-self-01"]
    assert one(tables(tube), "SELECT COUNT(*) FROM watched_videos") == 2


def test_a_new_upload_climbs_from_zero_and_page_and_table_agree_at_each_instant():
    tube = arrive(preloaded(), "new_video", {"video_id": DESK_SETUP})
    video = tube.videos[DESK_SETUP]
    assert video.view_count(UPLOAD_AT) == 0
    later = UPLOAD_AT + 300
    assert 0 < video.view_count(later) < video.view_count(UPLOAD_AT + 600)
    row = one(tables(tube, later), f"SELECT views FROM videos WHERE id='{DESK_SETUP}'")
    assert row == video.view_count(later)


def test_the_shown_view_count_changes_exactly_when_next_change_says():
    video = preloaded().videos[WALKTHROUGH]
    now, changes = 100.0, []
    # what the tag tells its page: the change, and how often an open page refreshes it
    page = SimpleNamespace(now=now, refreshes_at=lambda at, every: changes.append((at, every)))
    shown = display.views_text(display.moving(page, video.views))
    ((change, every),) = changes
    assert change is not None and change > now
    assert every == COUNT_REFRESH_S
    assert display.views_text(video.views.value_at(change - 0.01)) == shown
    assert display.views_text(video.views.value_at(change + 0.01)) != shown


def test_an_open_page_refreshes_view_counts_every_few_minutes_and_a_reload_at_once():
    """Was: the home page's view counts changed in 24 of 24 half-second samples."""
    from apps.kit.pages import Page

    video = preloaded().videos[WALKTHROUGH]
    page = Page(request=None, run=None, state=None, now=100.0)
    display.moving(page, video.views)
    # a reload reads anew at the count's next change; the open page is pushed at the refresh
    assert page.fresh_until is not None and 100.0 < page.fresh_until < COUNT_REFRESH_S
    assert page.next_change == COUNT_REFRESH_S
    assert page.reads_same_until == page.fresh_until


def test_search_covers_titles_descriptions_and_channel_names():
    tube = preloaded()
    assert [c.video.id for c in screens.search(tube, "skyward")] == [WALKTHROUGH]
    assert [c.video.id for c in screens.search(tube, "HEIST beats")] == []
    assert {c.video.id for c in screens.search(tube, "pixel forge")} == {
        WALKTHROUGH,
        "vid-pixel-02",
    }
    assert screens.search(tube, "crew assembly")[0].video.id == "vid-reel-01"


@pytest.mark.parametrize(
    ("value", "views", "subscribers"),
    [
        (512, "512 views", "512 subscribers"),
        (1318, "1.3K views", "1.32K subscribers"),
        (684_000, "684K views", "684K subscribers"),
        (1_420_000, "1.4M views", "1.42M subscribers"),
        (12_300_000, "12M views", "12.3M subscribers"),
    ],
)
def test_counts_read_as_on_youtube(value, views, subscribers):
    assert display.views_text(value) == views
    assert display.subscribers_text(value) == subscribers


def test_ages_read_as_on_youtube():
    assert display.ago(0, 30) == "Just now"
    assert display.ago(0, 61) == "1 minute ago"
    assert display.ago(0, 3 * 86400 + 5) == "3 days ago"
    assert display.ago(0, 15 * 86400) == "2 weeks ago"
    assert display.ago_changes_at(0, 61) == 120
