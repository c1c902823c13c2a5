"""Video thumbnails (apps.media.thumbnails): a picture's scene with a few words of the title in
large type baked into the SVG, 16:9 or (for shorts) 9:16, deterministic, served like every
generated image."""

from __future__ import annotations

from xml.etree import ElementTree

import pytest
from django.template import Context, Template
from django.test import Client

from apps.media import links, pictures, thumbnails
from apps.media.links import seeded_random

SVG = "{http://www.w3.org/2000/svg}"


def words_drawn(body: bytes) -> list[str]:
    """The lines of text drawn, in order (each line is drawn twice: its shadow, then itself)."""
    root = ElementTree.fromstring(body)
    return list(dict.fromkeys(t.text or "" for t in root.iter(f"{SVG}text")))


def test_the_url_carries_the_seed_the_subject_and_the_caption():
    assert (
        links.thumbnail_url("vid-pixel-01", "screenshot", "Skyward Colony 2")
        == "/media/thumbnails/screenshot/vid-pixel-01/skyward-colony-2.svg"
    )
    assert (
        links.thumbnail_url("vid-short-orbit-01", "abstract", "Saturn's Rings", tall=True)
        == "/media/tall-thumbnails/abstract/vid-short-orbit-01/saturns-rings.svg"
    )
    with pytest.raises(ValueError, match="allowed"):
        links.thumbnail_url("x", "volcano", "words")


def test_a_wide_thumbnail_draws_its_caption_over_the_scene_of_its_seed():
    body = thumbnails.wide("vid-pixel-01", "screenshot", "skyward-colony-2")
    root = ElementTree.fromstring(body)
    assert (root.get("width"), root.get("height")) == ("480", "270")
    assert " ".join(words_drawn(body)) == "SKYWARD COLONY 2"
    scene = pictures.SCENES["screenshot"](seeded_random("vid-pixel-01"))
    assert all(element in body.decode() for element in scene)  # the picture's own scene


def test_a_tall_thumbnail_is_drawn_9_by_16_with_its_caption():
    body = thumbnails.tall("vid-short-paw-01", "pet", "round-12")
    root = ElementTree.fromstring(body)
    assert (root.get("width"), root.get("height")) == ("270", "480")
    assert root.get("viewBox") == "0 0 270 480"
    assert words_drawn(body) == ["ROUND 12"]


def test_the_same_url_draws_the_same_bytes_and_another_caption_other_words():
    first = thumbnails.wide("vid-trail-03", "landscape", "winter-sunrise")
    assert first == thumbnails.wide("vid-trail-03", "landscape", "winter-sunrise")
    assert first != thumbnails.wide("vid-trail-03", "landscape", "summer-sunrise")
    tall = thumbnails.tall("vid-trail-03", "landscape", "winter-sunrise")
    assert tall == thumbnails.tall("vid-trail-03", "landscape", "winter-sunrise")


def test_an_empty_caption_draws_no_words():
    url = links.thumbnail_url("vid-paw-02", "pet", "")
    assert url.endswith("/unnamed.svg")
    assert words_drawn(thumbnails.wide("vid-paw-02", "pet", "unnamed")) == []


@pytest.mark.parametrize(
    ("title", "words"),
    [
        ("Skyward Colony 2: First 40 Turns, Explained", "Skyward Colony 2"),
        ("Why Saturn's Rings Won't Last Forever", "Saturn Rings"),
        ("Five Hand Grinders Under $100, Ranked", "Five Hand Grinders"),
        ("Every Group Chat Ever", "Every Group Chat"),
    ],
)
def test_a_title_gives_its_key_words(title, words):
    assert thumbnails.headline(title) == words


def test_it_is_served_immutable_and_bad_parts_are_a_404():
    client = Client()
    response = client.get("/media/thumbnails/food/vid-fork-02/crispiest-potatoes.svg")
    assert response.status_code == 200 and response["Content-Type"] == "image/svg+xml"
    assert response["Cache-Control"] == "public, max-age=31536000, immutable"
    assert b"CRISPIEST" in response.content
    tall = client.get("/media/tall-thumbnails/food/vid-short-brew-01/latte-heart.svg")
    assert tall.status_code == 200 and b'width="270"' in tall.content
    assert client.get("/media/thumbnails/volcano/x/y.svg").status_code == 404
    assert client.get("/media/thumbnails/food/Bad_Slug/y.svg").status_code == 404
    assert client.get("/media/thumbnails/food/x/Bad_Words.svg").status_code == 404


def test_the_tag_puts_the_words_in_the_image_not_the_page_text():
    html = Template(
        "{% load media %}{% thumbnail 'vid-fork-02' subject='food' title=t width=320 height=180 %}"
    ).render(Context({"t": "The Crispiest Oven Potatoes, Tested Five Ways"}))
    assert html == (
        '<img class="thumbnail wide" src="/media/thumbnails/food/vid-fork-02/'
        'crispiest-oven-potatoes.svg" alt="" width="320" height="180">'
    )
    tall = Template(
        "{% load media %}{% thumbnail 'v' subject='pet' caption='Round 12' tall=True "
        "width=210 height=374 %}"
    ).render(Context())
    assert 'src="/media/tall-thumbnails/pet/v/round-12.svg"' in tall and "tall" in tall
