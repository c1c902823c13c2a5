"""Names and addresses of generated images: the slug rule, the seeded randomness, the URLs.

A seed (a person's name, a company, a post id) becomes a slug — lowercase, every run of
characters other than [a-z0-9] turned into "-", trimmed, at most 80 characters — and the slug is
all a generator sees: the same name gives the same picture in every environment, and the URL
alone is enough to draw it again.
"""

from __future__ import annotations

import functools
import hashlib
import random
import re

from django.urls import reverse

from apps.media.pictures import check_subject

SLUG_LENGTH = 80
UNNAMED = "unnamed"  # the slug of a seed with no letter or digit at all
_NOT_SLUG = re.compile(r"[^a-z0-9]+")


@functools.lru_cache(maxsize=4096)
def slug(seed: str) -> str:
    """`"Maya O'Konjo"` → `"maya-o-konjo"`."""
    words = _NOT_SLUG.sub("-", str(seed).lower()).strip("-")
    return words[:SLUG_LENGTH].rstrip("-") or UNNAMED


def is_slug(text: str) -> bool:
    return bool(text) and slug(text) == text


def seeded_random(slug_text: str) -> random.Random:
    """The generator's randomness for `slug_text`: the same slug, the same draws, everywhere
    (sha256, unlike hash(), does not change between processes)."""
    digest = hashlib.sha256(slug_text.encode()).digest()
    return random.Random(int.from_bytes(digest[:16], "big"))


@functools.lru_cache(maxsize=4096)
def avatar_url(name: str) -> str:
    return reverse("media:avatar", kwargs={"slug": slug(name)})


@functools.lru_cache(maxsize=4096)
def logo_url(name: str) -> str:
    return reverse("media:logo", kwargs={"slug": slug(name)})


@functools.lru_cache(maxsize=4096)
def banner_url(seed: str) -> str:
    return reverse("media:banner", kwargs={"slug": slug(seed)})


@functools.lru_cache(maxsize=4096)
def picture_url(seed: str, subject: str = "landscape") -> str:
    """Raises ValueError naming the allowed subjects for an unknown `subject`."""
    return reverse("media:picture", kwargs={"subject": check_subject(subject), "slug": slug(seed)})


@functools.lru_cache(maxsize=4096)
def cover_url(seed: str) -> str:
    """Square album / playlist artwork."""
    return reverse("media:cover", kwargs={"slug": slug(seed)})


@functools.lru_cache(maxsize=4096)
def audio_url(seed: str) -> str:
    """A short generated music clip (WAV)."""
    return reverse("media:audio", kwargs={"slug": slug(seed)})


@functools.lru_cache(maxsize=4096)
def poster_url(seed: str, subject: str = "landscape", tall: bool = False) -> str:
    """A video's animated poster (the picture of the same seed and subject, moving, 16:9; for a
    short when `tall`, 9:16 in the portrait composition of its thumbnail)."""
    kwargs = {"subject": check_subject(subject), "slug": slug(seed)}
    return reverse("media:tall-poster" if tall else "media:poster", kwargs=kwargs)


@functools.lru_cache(maxsize=4096)
def thumbnail_url(seed: str, subject: str, caption: str, tall: bool = False) -> str:
    """A video thumbnail: the picture of `seed` and `subject` with `caption`'s words set large
    over it, 16:9 (or 9:16 for a short when `tall`). An empty caption draws no words; an
    apostrophe is dropped rather than splitting its word ("Saturn's" → SATURNS)."""
    words = caption.replace("'", "").replace("\u2019", "")
    kwargs = {"subject": check_subject(subject), "seed": slug(seed), "caption": slug(words)}
    return reverse("media:tall-thumbnail" if tall else "media:thumbnail", kwargs=kwargs)
