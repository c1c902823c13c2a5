"""The generated images by kind and slug, each drawn once per process and kept with its ETag.

Drawing is pure (the slug's seeded randomness in, SVG bytes out), so an image never changes
for a given slug and release: the bytes can be cached here, by the browser (immutable) and by
any proxy in between.
"""

from __future__ import annotations

import functools
import hashlib
from dataclasses import dataclass

from apps.media import banners, covers, faces, logos, pictures
from apps.media.links import seeded_random

IMAGES_KEPT = 2048  # a few pages' worth of faces, logos and pictures (a few KB each)
KINDS = {"avatars": faces.portrait, "logos": logos.mark, "banners": banners.banner}
KINDS["covers"] = covers.cover  # square album and playlist artwork


@dataclass(frozen=True)
class Image:
    body: bytes
    etag: str


def tagged(body: bytes) -> Image:
    """`body` with its ETag (a digest of the bytes), for any generated media file."""
    return _tagged(body)


def _tagged(body: bytes) -> Image:
    return Image(body, f'"{hashlib.sha256(body).hexdigest()[:20]}"')


@functools.lru_cache(maxsize=IMAGES_KEPT)
def drawn(kind: str, slug: str) -> Image:
    """The avatar, logo or banner of `slug` (`kind` one of KINDS)."""
    return _tagged(KINDS[kind](seeded_random(slug), slug))


@functools.lru_cache(maxsize=IMAGES_KEPT)
def drawn_picture(subject: str, slug: str) -> Image:
    """The picture of `slug` showing `subject` (one of pictures.SUBJECTS)."""
    return _tagged(pictures.picture(seeded_random(slug), slug, subject))
