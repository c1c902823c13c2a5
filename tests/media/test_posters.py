"""Animated posters (apps.media.posters): a video's picture, moving — the same scene as its
thumbnail, 16:9, looping SVG animation, deterministic, served like every generated image."""

from __future__ import annotations

from xml.etree import ElementTree

import pytest
from django.template import Context, Template, TemplateSyntaxError
from django.test import Client

from apps.media import links, pictures, posters
from apps.media.links import seeded_random

SVG = "{http://www.w3.org/2000/svg}"


def parsed(body: bytes) -> ElementTree.Element:
    return ElementTree.fromstring(body)


def test_the_url_follows_the_picture_shape():
    assert (
        links.poster_url("Vid Pixel 01", "screenshot")
        == "/media/posters/screenshot/vid-pixel-01.svg"
    )
    with pytest.raises(ValueError, match="allowed"):
        links.poster_url("x", "volcano")


def test_the_same_seed_gives_the_same_bytes_and_another_seed_another_poster():
    assert posters.poster("vid-trail-03", "landscape") == posters.poster(
        "vid-trail-03", "landscape"
    )
    assert posters.poster("vid-trail-03", "landscape") != posters.poster(
        "vid-trail-01", "landscape"
    )


def test_a_poster_is_16_by_9_and_loops_its_animation():
    root = parsed(posters.poster("vid-orbit-03", "abstract"))
    assert (root.get("width"), root.get("height")) == ("480", "270")
    assert root.get("viewBox").split()[2:] == ["480", "270"]
    animations = root.findall(f".//{SVG}animate")
    assert animations and all(a.get("repeatCount") == "indefinite" for a in animations)
    assert any(a.get("attributeName") == "viewBox" for a in animations)  # the camera moves


def test_it_draws_the_scene_of_the_thumbnail_with_the_same_seed():
    """Every element of the picture (its scene, from the same seeded draws) is in the poster."""
    scene = pictures.SCENES["food"](seeded_random("vid-fork-03"))
    body = posters.poster("vid-fork-03", "food").decode()
    assert all(element in body for element in scene)


def test_it_is_served_immutable_and_unknown_subjects_are_a_404():
    client = Client()
    response = client.get("/media/posters/city/vid-film-01.svg")
    assert response.status_code == 200 and response["Content-Type"] == "image/svg+xml"
    assert response["Cache-Control"] == "public, max-age=31536000, immutable"
    parsed(response.content)
    again = client.get("/media/posters/city/vid-film-01.svg", HTTP_IF_NONE_MATCH=response["ETag"])
    assert again.status_code == 304
    missing = client.get("/media/posters/volcano/vid-film-01.svg")
    assert missing.status_code == 404 and b"allowed landscape" in missing.content


def test_the_tag_renders_one_img_and_names_the_allowed_subjects():
    html = Template('{% load media %}{% poster "vid-pit-01" subject="city" label="Now playing" %}')
    assert html.render(Context()) == (
        '<img class="poster" src="/media/posters/city/vid-pit-01.svg" alt="Now playing" '
        'width="854" height="480">'
    )
    with pytest.raises(TemplateSyntaxError, match="allowed"):
        Template('{% load media %}{% poster "x" subject="volcano" %}').render(Context())


def test_a_short_has_a_9_by_16_poster_in_the_portrait_of_its_thumbnail():
    assert links.poster_url("vid-short-paw-01", "pet", tall=True) == (
        "/media/tall-posters/pet/vid-short-paw-01.svg"
    )
    root = parsed(posters.tall_poster("vid-short-paw-01", "pet"))
    assert (root.get("width"), root.get("height")) == ("270", "480")
    assert any(a.get("attributeName") == "viewBox" for a in root.findall(f".//{SVG}animate"))
    assert posters.tall_poster("vid-short-paw-01", "pet") == posters.tall_poster(
        "vid-short-paw-01", "pet"
    )
    response = Client().get("/media/tall-posters/pet/vid-short-paw-01.svg")
    assert response.status_code == 200 and b'height="480"' in response.content
