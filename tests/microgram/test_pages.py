"""MicroGram's pages through the test client: what each screen shows, and what its forms do."""

from __future__ import annotations

import re

from django.test import Client

from apps.kit.live import render_update
from apps.kit.screen_cache import CSRF_PLACEHOLDER
from events import lifecycle
from events.commands import current_state
from tests.microgram.cast import (
    ARRIVES_AT,
    CAST,
    DESK,
    EXPIRES_AT,
    LATE_STORY,
    MARCO,
    MARKET,
    POSTED_AT,
    SGRANT,
    STORIES,
    TRAY_EVENTS,
)


def test_home_shows_the_story_bar_the_feed_and_the_rail_badges(gram_url):
    html = Client().get(gram_url()).content.decode()
    assert 'aria-label="Story by rduarte, not seen yet"' in html
    assert "nhaddad" in html and "Saturday market haul" in html
    assert '<a class="hashtag" href="' in html and "#farmersmarket</a>" in html
    assert "View all 2 comments" in html
    assert ", 1 unread conversation" in html and ", 1 unread</span>" in html
    assert 'data-action="like_post"' in html and 'data-action="save_post"' in html
    # Cached rows carry this response's CSRF token, never a blank or the placeholder.
    tokens = set(re.findall(r'name="csrfmiddlewaretoken" value="([^"]*)"', html))
    assert len(tokens) == 1 and "" not in tokens and CSRF_PLACEHOLDER not in tokens


def test_a_post_is_404_until_it_arrives_then_opening_it_views_it(gram_run, gram_url):
    browser = Client()
    assert browser.get(gram_url(f"p/{DESK}/")).status_code == 404
    lifecycle.advance(gram_run, ARRIVES_AT)
    html = browser.get(gram_url(f"p/{DESK}/")).content.decode()
    assert html.count('class="comment" aria-label="Comment by') == 5
    assert current_state(gram_run).post_states[DESK].is_viewed
    feed = browser.get(gram_url()).content.decode()
    assert feed.index(f'id="post-{DESK}"') < feed.index(f'id="post-{MARKET}"')


def test_liking_from_the_feed_returns_to_the_post_with_the_heart_filled(gram_run, gram_url):
    browser = Client()
    response = browser.post(
        gram_url(f"p/{MARKET}/like_post"), HTTP_REFERER="http://testserver" + gram_url()
    )
    assert response.status_code == 302 and response.url.endswith(f"#post-{MARKET}")
    html = browser.get(gram_url()).content.decode()
    assert 'aria-label="Unlike post by nhaddad"' in html
    assert current_state(gram_run).post_states[MARKET].is_liked


def test_commenting_shows_the_comment_under_the_post(gram_url):
    browser = Client()
    browser.post(gram_url(f"p/{MARKET}/comment_post"), {"text": "Peach season!"})
    html = browser.get(gram_url(f"p/{MARKET}/")).content.decode()
    assert "Peach season!" in html and 'aria-label="Comment by ctaylor"' in html


def test_opening_a_story_watches_it_and_links_to_the_next(gram_run, gram_url):
    newest, older = STORIES[1], STORIES[0]
    html = Client().get(gram_url(f"stories/{newest}/")).content.decode()
    assert f'href="{gram_url(f"stories/{older}/")}" aria-label="Next story"' in html
    assert newest in current_state(gram_run).viewed_stories
    home = Client().get(gram_url()).content.decode()
    assert 'aria-label="Story by amenon, seen"' in home
    assert home.index("Story by rduarte, not seen yet") < home.index("Story by amenon, seen")


def pushed_arrows(run, url: str) -> list[tuple[str, str]]:
    """(story id, "Previous" | "Next") of the viewer's arrows in a live push of `url`."""
    html = "".join(outer for _, outer in render_update(run, url).regions)
    return re.findall(r'stories/([^/"]+)/" aria-label="(Previous|Next) story"', html)


def test_the_story_viewers_arrows_are_pushed_as_the_tray_changes(db):
    run = CAST.start(events=TRAY_EVENTS)
    url = f"/r/{run.token}/microgram/stories/{SGRANT}/"
    assert Client().get(url).status_code == 200
    oldest, middle = STORIES
    assert pushed_arrows(run, url) == [(middle, "Next")]
    lifecycle.advance(run, EXPIRES_AT)  # the story after the open one expires: skipped
    assert pushed_arrows(run, url) == [(oldest, "Next")]
    lifecycle.advance(run, POSTED_AT)  # a new one: reachable
    assert pushed_arrows(run, url) == [(LATE_STORY, "Previous"), (oldest, "Next")]


def test_opening_a_thread_reads_it_and_sending_adds_a_bubble(gram_run, gram_url):
    browser = Client()
    inbox = browser.get(gram_url("direct/inbox/")).content.decode()
    assert 'aria-label="Unread: tlindqvist, Actually the big one, obviously"' in inbox
    thread = browser.get(gram_url("direct/t/dm-tobias/")).content.decode()
    assert "Saw your sourdough post" in thread
    assert current_state(gram_run).read_messages["dm-tobias-m4"] is True
    browser.post(gram_url("direct/t/dm-tobias/send"), {"text": "Big one it is"})
    thread = browser.get(gram_url("direct/t/dm-tobias/")).content.decode()
    assert 'aria-label="You: Big one it is"' in thread
    assert browser.get(gram_url("direct/t/dm-rosa/")).status_code == 404


def test_activity_read_goes_to_the_person_and_follow_back_works(gram_run, gram_url):
    browser = Client()
    html = browser.get(gram_url("activity/")).content.decode()
    assert 'aria-label="Unread: mbellini started following you."' in html
    response = browser.post(gram_url("activity/read"), {"activity_id": "act-10"})
    assert response.status_code == 302 and response.url.endswith(f"profile/{MARCO}/")
    browser.post(gram_url(f"profile/{MARCO}/follow"))
    profile = browser.get(gram_url(f"profile/{MARCO}/")).content.decode()
    assert 'aria-label="Following mbellini: unfollow"' in profile
    assert current_state(gram_run).followed == (MARCO,)


def test_profile_saved_tab_explore_and_search(gram_url):
    browser = Client()
    browser.post(gram_url(f"p/{MARKET}/save_post"))
    me = browser.get(gram_url("profile/user000/")).content.decode()
    assert "847" in me and "followers" in me and "Chris Taylor" in me
    saved = browser.get(gram_url("profile/user000/?tab=saved")).content.decode()
    assert 'aria-label="Saved posts"' in saved and "post-market-haul" in saved
    explore = browser.get(gram_url("explore/?q=tomatoes")).content.decode()
    assert "1 post matching" in explore
    found = browser.get(gram_url("search/?q=noor")).content.decode()
    assert "nhaddad" in found
    assert "onordby" not in browser.get(gram_url("search/?q=nordby")).content.decode()
    assert browser.get(gram_url("profile/user051/")).status_code == 404  # not seen yet
    assert browser.get(gram_url("?page=99")).status_code == 400


def test_the_message_button_opens_a_thread_once_followed_and_posts_can_be_shared(
    gram_run, gram_url
):
    browser = Client()
    profile = browser.get(gram_url(f"profile/{MARCO}/")).content.decode()
    assert 'data-action="start_conversation"' not in profile
    browser.post(gram_url(f"profile/{MARCO}/follow"))
    response = browser.post(gram_url(f"profile/{MARCO}/message"))
    assert response.status_code == 302 and "/direct/t/user-thread-" in response.url
    post = browser.get(gram_url(f"p/{MARKET}/")).content.decode()
    assert 'data-action="share_post"' in post and '<option value="dm-maya">' in post
    browser.post(gram_url(f"p/{MARKET}/share"), {"conversation_id": "dm-maya", "text": "Look!"})
    thread = browser.get(gram_url("direct/t/dm-maya/")).content.decode()
    assert 'aria-label="You: shared a post by nhaddad, Look!"' in thread
    assert current_state(gram_run).sent[-1].post_id == MARKET
