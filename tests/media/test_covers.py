"""Covers: square album and playlist artwork — the same seed draws the same bytes, different
seeds differ, the title is set from the slug, and the tag and URL follow the media interface."""

from __future__ import annotations

from xml.etree import ElementTree

from django.template import Context, Template
from django.test import Client

from apps.media import covers, images, links

SVG = "{http://www.w3.org/2000/svg}"
SEEDS = ["Late Night Jazz", "Morning Coffee", "Side B: Freeways", "Blues After Midnight", "x"]


def drawn(slug: str) -> ElementTree.Element:
    return ElementTree.fromstring(images.drawn("covers", slug).body)


def test_a_cover_is_a_square_svg_and_the_same_slug_draws_the_same_bytes():
    for seed in SEEDS:
        slug = links.slug(seed)
        root = drawn(slug)
        assert (root.get("width"), root.get("height")) == ("300", "300")
        again = covers.cover(links.seeded_random(slug), slug)
        assert again == images.drawn("covers", slug).body


def test_different_seeds_draw_different_covers():
    bodies = {images.drawn("covers", links.slug(seed)).body for seed in SEEDS}
    assert len(bodies) == len(SEEDS)


def test_the_title_comes_from_the_slug_in_capitals_on_at_most_three_lines():
    assert covers.title_lines("late-night-jazz") == ["LATE NIGHT", "JAZZ"]
    assert covers.title_lines("a-very-long-playlist-name-that-goes-on") == [
        "A VERY LONG",
        "PLAYLIST",
        "NAME THAT",
    ]
    written = [
        "".join(t.itertext()) for seed in SEEDS for t in drawn(links.slug(seed)).iter(SVG + "text")
    ]
    assert all(line == line.upper() for line in written)


def test_the_tag_and_the_url_follow_the_interface():
    assert links.cover_url("Late Night Jazz") == "/media/covers/late-night-jazz.svg"
    html = Template('{% load media %}{% cover "Late Night Jazz" size=48 %}').render(Context())
    assert html == (
        '<img class="cover" src="/media/covers/late-night-jazz.svg" alt="" width="48" height="48">'
    )


def test_covers_are_served_with_immutable_caching():
    response = Client().get("/media/covers/late-night-jazz.svg")
    assert response.status_code == 200
    assert response["Content-Type"] == "image/svg+xml"
    assert response["Cache-Control"] == "public, max-age=31536000, immutable"
    assert Client().get("/media/covers/Not%20A%20Slug.svg").status_code == 404
