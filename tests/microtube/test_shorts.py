"""Shorts: a run whose catalog marks shorts shows only them on the Shorts page and Home's shelf,
each with a portrait (9:16) thumbnail; a run with none (the original's catalog) keeps the
fallback of the first Home videos, as the original did."""

from __future__ import annotations

import re

from django.test import Client

from events import lifecycle
from tests.microtube.cast import CAST, PRELOAD, WALKTHROUGH

SHORTS = ["vid-short-pixel-01", "vid-short-self-01"]


def with_shorts():
    """The cast, with two of our shorts preloaded beside its long videos."""
    preload = {**PRELOAD, "video_ids": PRELOAD["video_ids"] + SHORTS}
    events = [{"time": 0.0, "type": "preload_videos", "payload": preload}]
    return CAST.start(events=events + CAST.scenario["events"][1:])


def shelf_of(html: str) -> str:
    return html.split('id="shorts-shelf"', 1)[1].split("</ul>", 1)[0]


def test_the_shorts_page_lists_only_the_shorts_with_portrait_thumbnails(db):
    run = with_shorts()
    root = f"/r/{run.token}/microtube/"
    shelf = shelf_of(Client().get(root + "shorts").content.decode())
    assert re.findall(r'href="[^"]*/shorts/([^"]+)"', shelf) == [
        "vid-short-pixel-01",
        "vid-short-self-01",
    ]
    assert shelf.count("/media/tall-thumbnails/") == 2 and "/media/pictures/" not in shelf
    assert "/media/tall-thumbnails/screenshot/vid-short-pixel-01/trade-route-trick.svg" in shelf
    assert WALKTHROUGH not in shelf
    home = Client().get(root).content.decode()
    assert 'class="yt-shorts-shelf"' in home and home.count("/media/tall-thumbnails/") == 2
    lifecycle.advance(run, 1.0)  # the short's player plays the next short, not a long video
    player = Client().get(root + "shorts/vid-short-pixel-01").content.decode()
    assert f'href="{root}shorts/vid-short-self-01"' in player
    assert "/media/tall-posters/screenshot/vid-short-pixel-01.svg" in player  # a portrait player


def test_without_shorts_the_page_falls_back_to_the_first_home_videos(tube_url):
    shelf = shelf_of(Client().get(tube_url("shorts")).content.decode())
    assert f"/shorts/{WALKTHROUGH}" in shelf and "/media/tall-thumbnails/" not in shelf
    assert f"/media/pictures/screenshot/{WALKTHROUGH}.svg" in shelf
    home = Client().get(tube_url()).content.decode()
    assert "yt-shorts-shelf" not in home
    player = Client().get(tube_url(f"shorts/{WALKTHROUGH}")).content.decode()
    assert f"/media/posters/screenshot/{WALKTHROUGH}.svg" in player  # as before


def test_every_card_thumbnail_carries_its_caption(tube_url):
    home = Client().get(tube_url()).content.decode()
    assert "/media/thumbnails/screenshot/vid-pixel-01/first-40-turns.svg" in home
    assert "/media/pictures/" not in home.split('id="home-grid"', 1)[1]
