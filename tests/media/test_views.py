"""/media/…: images served as SVG with a year's immutable caching and an ETag; anything we do not
draw is a 404 whose one line says why."""

from __future__ import annotations

from xml.etree import ElementTree

import pytest
from django.test import Client

from apps.media import links, pictures

IMMUTABLE = "public, max-age=31536000, immutable"


@pytest.fixture
def client() -> Client:
    return Client()


def served(client: Client, url: str):
    response = client.get(url)
    assert response.status_code == 200, response.content
    assert response["Content-Type"] == "image/svg+xml"
    assert response["Cache-Control"] == IMMUTABLE
    assert response["ETag"].startswith('"')
    ElementTree.fromstring(response.content)
    return response


def test_urls_follow_the_interface():
    assert links.avatar_url("Maya Okonjo") == "/media/avatars/maya-okonjo.svg"
    assert links.logo_url("Acme Robotics") == "/media/logos/acme-robotics.svg"
    assert links.banner_url("Maya Okonjo") == "/media/banners/maya-okonjo.svg"
    assert links.picture_url("Post 7", "food") == "/media/pictures/food/post-7.svg"
    assert links.picture_url("Post 7") == "/media/pictures/landscape/post-7.svg"


def test_avatars_logos_and_banners_are_served(client):
    for url in (
        links.avatar_url("Maya Okonjo"),
        links.logo_url("Acme Robotics"),
        links.banner_url("Maya Okonjo"),
    ):
        served(client, url)


@pytest.mark.parametrize("subject", pictures.SUBJECTS)
def test_every_picture_subject_is_served(client, subject):
    served(client, links.picture_url("post-1", subject))


def test_the_same_url_serves_the_same_bytes_and_etag(client):
    url = links.avatar_url("Chris Taylor")
    first, second = client.get(url), client.get(url)
    assert first.content == second.content
    assert first["ETag"] == second["ETag"]


def test_a_matching_etag_gets_a_304(client):
    url = links.logo_url("Globex")
    etag = served(client, url)["ETag"]
    response = client.get(url, headers={"If-None-Match": etag})
    assert response.status_code == 304
    assert response.content == b""
    assert response["ETag"] == etag


def test_head_is_allowed_and_post_is_not(client):
    url = links.avatar_url("Chris Taylor")
    assert client.head(url).status_code == 200
    assert client.post(url).status_code == 405


def test_an_unknown_subject_is_a_404_naming_the_subjects(client):
    response = client.get("/media/pictures/selfie/post-1.svg")
    assert response.status_code == 404
    reason = response.content.decode()
    assert reason.count("\n") == 1
    assert "'selfie'" in reason and "landscape, city, food" in reason


def test_an_unknown_kind_is_a_404_naming_the_kinds(client):
    response = client.get("/media/portraits/maya-okonjo.svg")
    assert response.status_code == 404
    assert "avatars, logos, banners" in response.content.decode()


@pytest.mark.parametrize("slug", ["Maya-Okonjo", "maya--okonjo", "-maya", "a" * 81])
def test_a_name_that_breaks_the_slug_rule_is_a_404(client, slug):
    response = client.get(f"/media/avatars/{slug}.svg")
    assert response.status_code == 404
    assert "not a media slug" in response.content.decode()
