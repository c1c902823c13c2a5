"""Serving generated images: SVG, cached for a year (a URL's image never changes), with an ETag
so a revalidating client gets a 304. Outside any run: no session, no database."""

from __future__ import annotations

from django.http import HttpRequest, HttpResponse, HttpResponseNotFound, HttpResponseNotModified
from django.views.decorators.http import require_safe

from apps.media import audio as clips
from apps.media import images, links, pictures, posters, thumbnails

CACHE_FOREVER = "public, max-age=31536000, immutable"


def _served(
    request: HttpRequest, image: images.Image, content_type: str = "image/svg+xml"
) -> HttpResponse:
    if request.headers.get("If-None-Match") == image.etag:
        response: HttpResponse = HttpResponseNotModified()
    else:
        response = HttpResponse(image.body, content_type=content_type)
    response["Cache-Control"] = CACHE_FOREVER
    response["ETag"] = image.etag
    return response


def _not_found(reason: str) -> HttpResponse:
    return HttpResponseNotFound(reason + "\n", content_type="text/plain; charset=utf-8")


def _bad_slug(slug: str) -> HttpResponse | None:
    if links.is_slug(slug):
        return None
    return _not_found(f"not a media slug: {slug[:100]!r} (lowercase a-z, 0-9 and '-', at most 80)")


@require_safe
def drawn(request: HttpRequest, kind: str, slug: str) -> HttpResponse:
    """/media/avatars/<slug>.svg, /media/logos/…, /media/banners/…"""
    if kind not in images.KINDS:
        return _not_found(f"unknown media kind {kind!r}: allowed {', '.join(images.KINDS)}")
    return _bad_slug(slug) or _served(request, images.drawn(kind, slug))


@require_safe
def picture(request: HttpRequest, subject: str, slug: str) -> HttpResponse:
    """/media/pictures/<subject>/<slug>.svg"""
    if subject not in pictures.SUBJECTS:
        return _not_found(
            f"unknown picture subject {subject!r}: allowed {', '.join(pictures.SUBJECTS)}"
        )
    return _bad_slug(slug) or _served(request, images.drawn_picture(subject, slug))


@require_safe
def audio(request: HttpRequest, slug: str) -> HttpResponse:
    """/media/audio/<slug>.wav: a short generated music clip, cached like the images."""
    return _bad_slug(slug) or _served(request, clips.clip(slug), "audio/wav")


@require_safe
def poster(request: HttpRequest, subject: str, slug: str, tall: bool = False) -> HttpResponse:
    """/media/posters/<subject>/<slug>.svg: the animated poster of a video (apps.media.posters);
    /media/tall-posters/…: a short's, 9:16."""
    if subject not in pictures.SUBJECTS:
        return _not_found(
            f"unknown poster subject {subject!r}: allowed {', '.join(pictures.SUBJECTS)}"
        )
    return _bad_slug(slug) or _served(request, posters.drawn_poster(subject, slug, tall))


@require_safe
def thumbnail(
    request: HttpRequest, shape: str, subject: str, seed: str, caption: str
) -> HttpResponse:
    """/media/thumbnails/<subject>/<seed>/<caption>.svg (16:9) and /media/tall-thumbnails/…
    (9:16): a video's picture with its caption's words (apps.media.thumbnails)."""
    if subject not in pictures.SUBJECTS:
        return _not_found(
            f"unknown thumbnail subject {subject!r}: allowed {', '.join(pictures.SUBJECTS)}"
        )
    return (
        _bad_slug(seed)
        or _bad_slug(caption)
        or _served(request, thumbnails.drawn_thumbnail(shape, subject, seed, caption))
    )
