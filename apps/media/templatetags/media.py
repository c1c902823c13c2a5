"""Generated images in templates: `{% load media %}` then

    {% avatar name size=32 %}             a face; decorative (alt="") unless label="…"
    {% logo name size=40 %}               a company / team mark
    {% banner seed %}                     a wide cover (CSS makes it 100% wide)
    {% picture seed subject="landscape" width=480 height=320 label="…" %}
    {% thumbnail seed subject="landscape" title="…" tall=False %}   a video's, with its words

Each renders one <img> with its width and height set (no layout shift while it loads). The
label only ever goes into the alt attribute, escaped. Optional `class="…"` adds classes.
"""

from __future__ import annotations

from django import template
from django.utils.html import format_html
from django.utils.safestring import SafeString

from apps.media import links, pictures, thumbnails

register = template.Library()


def _img(
    kind: str, src: str, width: object, height: object, label: str, classes: str
) -> SafeString:
    return format_html(
        '<img class="{}" src="{}" alt="{}" width="{}" height="{}">',
        f"{kind} {classes}".strip(),
        src,
        label,
        _pixels(width, "width"),
        _pixels(height, "height"),
    )


def _pixels(value: object, name: str) -> int:
    try:
        pixels = int(value)  # type: ignore[call-overload]
    except (TypeError, ValueError):
        pixels = 0
    if pixels <= 0:
        raise template.TemplateSyntaxError(
            f"media tag {name} must be a positive number of pixels, got {value!r}"
        )
    return pixels


@register.simple_tag
def avatar(name: str, size: int = 32, label: str = "", **options: str) -> SafeString:
    """The face of the person called `name` (the same face in every environment)."""
    return _img("avatar", links.avatar_url(name), size, size, label, options.get("class", ""))


@register.simple_tag
def logo(name: str, size: int = 40, label: str = "", **options: str) -> SafeString:
    """The mark of the company, team or brand called `name`."""
    return _img("logo", links.logo_url(name), size, size, label, options.get("class", ""))


@register.simple_tag
def banner(
    seed: str, width: int = 1200, height: int = 300, label: str = "", **options: str
) -> SafeString:
    """A cover banner (4:1 drawing; it covers any box it is given)."""
    return _img("banner", links.banner_url(seed), width, height, label, options.get("class", ""))


@register.simple_tag
def picture(
    seed: str,
    subject: str = "landscape",
    width: int = 480,
    height: int = 320,
    label: str = "",
    **options: str,
) -> SafeString:
    """A photo-like illustration of `subject` (3:2 drawing; it covers any box it is given)."""
    if subject not in pictures.SUBJECTS:
        raise template.TemplateSyntaxError(
            f"{{% picture %}} subject {subject!r}: allowed {', '.join(pictures.SUBJECTS)}"
        )
    return _img(
        "picture", links.picture_url(seed, subject), width, height, label, options.get("class", "")
    )


@register.simple_tag
def cover(seed: str, size: int = 160, label: str = "", **options: str) -> SafeString:
    """Square album / playlist artwork for `seed` (most styles set its words in large type)."""
    return _img("cover", links.cover_url(seed), size, size, label, options.get("class", ""))


@register.simple_tag
def poster(
    seed: str,
    subject: str = "landscape",
    width: int = 854,
    height: int = 480,
    label: str = "",
    tall: bool = False,
    **options: str,
) -> SafeString:
    """A video's animated poster: the picture of `seed` and `subject`, moving (16:9, looping;
    9:16 in a short's portrait composition when `tall`)."""
    if subject not in pictures.SUBJECTS:
        raise template.TemplateSyntaxError(
            f"{{% poster %}} subject {subject!r}: allowed {', '.join(pictures.SUBJECTS)}"
        )
    return _img(
        "poster",
        links.poster_url(seed, subject, tall=bool(tall)),
        width,
        height,
        label,
        options.get("class", ""),
    )


@register.simple_tag
def thumbnail(
    seed: str,
    subject: str = "landscape",
    title: str = "",
    caption: str = "",
    width: int = 320,
    height: int = 180,
    tall: bool = False,
    label: str = "",
    **options: str,
) -> SafeString:
    """A video thumbnail: the picture of `seed` and `subject` with `caption` (else the key words
    of `title`) in large type drawn into the image (16:9; 9:16 when `tall`, for a short). The words are in the
    picture, not the page's text, so a page reading its title once still reads it once."""
    if subject not in pictures.SUBJECTS:
        raise template.TemplateSyntaxError(
            f"{{% thumbnail %}} subject {subject!r}: allowed {', '.join(pictures.SUBJECTS)}"
        )
    src = links.thumbnail_url(seed, subject, caption or thumbnails.headline(title), tall=bool(tall))
    classes = f"{'tall' if tall else 'wide'} {options.get('class', '')}"
    return _img("thumbnail", src, width, height, label, classes)
