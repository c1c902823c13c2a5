"""MicroTube's pages through the test client: what each screen shows, and what its forms do."""

from __future__ import annotations

from django.test import Client

from apps.kit.live import render_update
from events import lifecycle
from events.commands import current_state
from tests.microtube.cast import CAST, DESK_SETUP, UPLOAD_AT, WALKTHROUGH

REEL = "vid-reel-01"  # Reel Talk's, public throughout


def test_home_shows_cards_with_channel_views_age_and_the_bell_badge(tube_url):
    html = Client().get(tube_url()).content.decode()
    assert "Skyward Colony 2: First 40 Turns, Explained" in html
    assert "684K views • 2 days ago" in html and "24:18" in html
    assert 'aria-label="Notifications (1 unread)"' in html
    assert '<span class="yt-badge">1</span>' in html
    assert "Pixel Forge" in html  # in the guide's subscriptions and on its cards


def test_an_upload_is_a_404_until_it_arrives_then_tops_subscriptions(tube_run, tube_url):
    browser = Client()
    assert browser.get(tube_url(f"watch?v={DESK_SETUP}")).status_code == 404
    lifecycle.advance(tube_run, UPLOAD_AT)
    page = browser.get(tube_url("feed/subscriptions")).content.decode()
    feed = page.split('id="subscriptions-feed"', 1)[1]
    assert feed.index("Building a Quiet Gaming Desk Setup") < feed.index("Skyward Colony 2")
    assert "0 views • Just now" in feed
    assert 'aria-label="Notifications (2 unread)"' in browser.get(tube_url()).content.decode()


def test_opening_the_watch_page_is_watching_and_shows_comments(tube_run, tube_url):
    html = Client().get(tube_url(f"watch?v={WALKTHROUGH}")).content.decode()
    assert "2 Comments" in html and "Skyward Colony 2 is the first sequel" in html
    assert "1.42M subscribers" in html and 'data-action="like_video"' in html
    assert 'src="/media/posters/screenshot/vid-pixel-01.svg"' in html
    assert current_state(tube_run).watched == ("vid-self-01", WALKTHROUGH)
    history = Client().get(tube_url("feed/history")).content.decode()
    assert history.index("Skyward Colony 2") < history.index("V4 Project at Mission Cliffs")


def test_liking_through_the_page_shows_liked_and_can_be_undone(tube_run, tube_url):
    browser = Client()
    response = browser.post(tube_url(f"videos/{WALKTHROUGH}/like_video"), follow=True)
    html = response.content.decode()
    assert 'data-action="unlike_video"' in html and 'aria-label="Remove like' in html
    assert current_state(tube_run).video_states[WALKTHROUGH].liked
    browser.post(tube_url(f"videos/{WALKTHROUGH}/unlike_video"))
    assert not current_state(tube_run).video_states[WALKTHROUGH].liked


def test_a_posted_comment_appears_first_under_the_video(tube_url):
    response = Client().post(
        tube_url(f"videos/{WALKTHROUGH}/post_comment"), {"content": "River trade wins"}, follow=True
    )
    html = response.content.decode()
    assert "Comment added" in html and "3 Comments" in html
    assert html.index("River trade wins") < html.index("Skyward Colony 2 is the first sequel")


def test_subscribing_from_a_channel_page_adds_it_to_the_guide(tube_run, tube_url):
    browser = Client()
    page = browser.get(tube_url("channel/ch-reel-talk")).content.decode()
    assert "1.73M subscribers" in page and 'data-action="subscribe"' in page
    after = browser.post(tube_url("channel/ch-reel-talk/subscribe"), follow=True).content.decode()
    assert "Subscription added" in after and 'aria-label="Unsubscribe from Reel Talk"' in after
    assert current_state(tube_run).is_subscribed("ch-reel-talk")


def test_opening_a_notification_reads_it_and_goes_to_what_it_is_about(tube_run, tube_url):
    lifecycle.advance(tube_run, UPLOAD_AT)
    browser = Client()
    response = browser.post(
        tube_url("notifications/read_notification"), {"notification_id": "notif-08"}
    )
    assert response.status_code == 302 and response.url.endswith("/channel/ch-pixel-forge")
    assert current_state(tube_run).notification_states["notif-08"].read
    browser.post(tube_url("notifications/dismiss_notification"), {"notification_id": "notif-01"})
    html = browser.get(tube_url("notifications")).content.decode()
    assert "2 notifications, 0 unread" in html and "Kitchen Table Code uploaded" not in html


def test_saving_to_watch_later_and_a_new_playlist(tube_run, tube_url):
    browser = Client()
    browser.post(tube_url(f"videos/{WALKTHROUGH}/save_video"))
    later = browser.get(tube_url("playlist?list=WL")).content.decode()
    assert "Watch later" in later and "1 video" in later and "Skyward Colony 2" in later
    created = browser.post(
        tube_url("playlists/new"), {"name": "Strategy night", "video_id": WALKTHROUGH}, follow=True
    ).content.decode()
    assert "Created playlist Strategy night" in created
    assert current_state(tube_run).playlists["pl-user-1"].video_ids == (WALKTHROUGH,)
    assert "Strategy night" in browser.get(tube_url("feed/playlists")).content.decode()


def test_a_video_made_private_keeps_its_row_in_a_playlist_as_youtubes_private_video(db):
    made_private_at = 30.0
    run = CAST.start(
        events=[
            CAST.scenario["events"][0],  # the preload
            {
                "time": made_private_at,
                "type": "make_private",
                "payload": {"video_id": WALKTHROUGH},
            },
        ]
    )
    root, browser = f"/r/{run.token}/microtube/", Client()
    for video in (WALKTHROUGH, REEL):
        browser.post(f"{root}videos/{video}/save_video")
    lifecycle.advance(run, made_private_at)

    page = browser.get(root + "playlist?list=WL").content.decode()
    videos = page.split('id="playlist-videos"', 1)[1]
    row = videos.split("</article>", 1)[0]  # the first saved, made private since
    assert 'aria-label="[Private video]"' in row and 'class="yt-thumb-empty"' in row
    assert f'<a href="{root}watch?v={WALKTHROUGH}">[Private video]</a>' in row
    assert "Skyward Colony 2" not in videos and "Pixel Forge" not in row and "views" not in row
    assert "Private • 2 videos" in page  # YouTube still counts it
    hero = page.split('class="yt-playlist-hero"', 1)[1].split("</section>", 1)[0]
    assert REEL in hero and WALKTHROUGH not in hero  # the first public one's thumbnail
    assert "Watch later, 2 videos" in browser.get(root + "feed/playlists").content.decode()
    watch = browser.get(f"{root}watch?v={WALKTHROUGH}").content.decode()
    assert "This video is private." in watch


def test_search_channel_tabs_and_bad_urls(tube_url):
    browser = Client()
    found = browser.get(tube_url("results?search_query=crew+assembly")).content.decode()
    assert "1 result for" in found and "Every Heist Movie Follows These Five Beats" in found
    about = browser.get(tube_url("channel/ch-pixel-forge?tab=about")).content.decode()
    assert "@PixelForge" in about and "612 videos" in about
    assert browser.get(tube_url("channel/ch-nobody")).status_code == 404
    assert browser.get(tube_url("channel/ch-pixel-forge?tab=bogus")).status_code == 404
    assert browser.get(tube_url("playlist?list=nope")).status_code == 404
    refused = browser.post(tube_url(f"videos/{WALKTHROUGH}/explode"))
    assert refused.status_code == 404 and "allowed: like_video" in refused.content.decode()


def test_shorts_shelf_and_player_rate_and_return_to_the_short(tube_run, tube_url):
    browser = Client()
    shelf = browser.get(tube_url("shorts")).content.decode()
    assert f'href="/r/{tube_run.token}/microtube/shorts/{WALKTHROUGH}"' in shelf
    player = browser.get(tube_url(f"shorts/{WALKTHROUGH}")).content.decode()
    assert 'aria-label="Next short"' in player and 'data-action="like_video"' in player
    response = browser.post(tube_url(f"videos/{WALKTHROUGH}/like_video"), {"back": "shorts"})
    assert response.url.endswith(f"/shorts/{WALKTHROUGH}")
    state = current_state(tube_run)
    assert state.video_states[WALKTHROUGH].liked and WALKTHROUGH not in state.watched
    assert browser.get(tube_url(f"shorts/{DESK_SETUP}")).status_code == 404


def test_an_upload_is_pushed_to_the_open_home_page_and_the_bell(tube_run, tube_url):
    lifecycle.advance(tube_run, UPLOAD_AT)
    update = render_update(tube_run, tube_url())
    regions = dict(update.regions)
    assert "Building a Quiet Gaming Desk Setup" in regions["home-grid"]
    assert 'aria-label="Notifications (2 unread)"' in regions["bell"]
    assert "Pixel Forge is going live in 30 minutes" in regions["bell-list"]
    # The new video's views climb: the page says when its "N views" next changes.
    assert update.next_change is not None and update.next_change > UPLOAD_AT
