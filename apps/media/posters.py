"""Posters: a video's animated still, for players. The scene of the video's picture (same seed
and subject, so the same elements as its thumbnail), cropped to 16:9 and brought to life with
SVG animation (SMIL, which browsers play inside an <img>): a slow camera push-in and pan, a band
of light sweeping across, motes drifting up. Eight seconds, looping; no script, no network.
"""

from __future__ import annotations

import functools
import random
from xml.sax.saxutils import escape

from apps.media import images, thumbnails
from apps.media.links import seeded_random
from apps.media.pictures import HEIGHT as PICTURE_HEIGHT
from apps.media.pictures import SCENES, check_subject
from apps.media.svg import el, linear_gradient

WIDTH, HEIGHT = 480, 270  # 16:9, cut from the middle of the 480×320 picture
LOOP_S = 8
POSTERS_KEPT = 512


def _camera(rng: random.Random) -> str:
    """The root viewBox moving: from the full frame to a closer one and back (a Ken Burns)."""
    top = (PICTURE_HEIGHT - HEIGHT) / 2
    zoom = rng.uniform(0.84, 0.9)
    width, height = WIDTH * zoom, HEIGHT * zoom
    x = rng.uniform(0, WIDTH - width)
    y = top + rng.uniform(0, HEIGHT - height)
    return _viewbox_loop(
        f"0 {top:.1f} {WIDTH} {HEIGHT}", f"{x:.1f} {y:.1f} {width:.1f} {height:.1f}"
    )


def _viewbox_loop(start: str, close: str) -> str:
    """The root viewBox easing from `start` to `close` and back, over one loop."""
    return el(
        "animate",
        attributeName="viewBox",
        values=f"{start};{close};{start}",
        keyTimes="0;0.5;1",
        calcMode="spline",
        keySplines="0.42 0 0.58 1;0.42 0 0.58 1",
        dur=f"{LOOP_S}s",
        repeatCount="indefinite",
    )


def _light_sweep(rng: random.Random) -> list[str]:
    """A soft diagonal band of light crossing the frame once per loop."""
    band = el(
        "rect",
        el(
            "animate",
            attributeName="x",
            values=f"-200;{WIDTH + 60}",
            dur=f"{LOOP_S}s",
            begin=f"{rng.uniform(0, 2):.1f}s",
            repeatCount="indefinite",
        ),
        x=-200,
        y=-40,
        width=140,
        height=PICTURE_HEIGHT + 80,
        fill="url(#poster-sweep)",
        transform=f"skewX({rng.choice((-18, -12, 12, 18))})",
    )
    gradient = linear_gradient(
        "poster-sweep",
        [(0, "rgba(255,255,255,0)"), (0.5, "rgba(255,255,255,0.28)"), (1, "rgba(255,255,255,0)")],
        vertical=False,
    )
    return [el("defs", gradient), band]


def _looping(attribute: str, values: str, begin: str) -> str:
    return el(
        "animate",
        attributeName=attribute,
        values=values,
        dur=f"{LOOP_S}s",
        begin=begin,
        repeatCount="indefinite",
    )


def _motes(rng: random.Random) -> list[str]:
    """Specks of light drifting upwards, each on its own phase."""
    motes = []
    for _ in range(rng.randint(8, 14)):
        x, r = rng.uniform(0, WIDTH), rng.uniform(1.5, 4)
        rise = rng.uniform(60, 160)
        y = rng.uniform(120, PICTURE_HEIGHT)
        begin = f"{rng.uniform(0, LOOP_S):.1f}s"
        motes.append(
            el(
                "circle",
                _looping("cy", f"{y:.0f};{y - rise:.0f}", begin),
                _looping("opacity", "0;0.8;0", begin),
                cx=x,
                cy=y,
                r=r,
                fill="#ffffff",
                opacity=0,
            )
        )
    return motes


def poster(slug: str, subject: str) -> bytes:
    """The animated poster of `slug`: the picture's scene drawn from the same seeded draws (so
    it matches the thumbnail), then the animation from the draws that follow."""
    rng = seeded_random(slug)
    scene = SCENES[check_subject(subject)](rng)
    top = (PICTURE_HEIGHT - HEIGHT) / 2
    root = el(
        "svg",
        el("title", escape(f"{subject} {slug} (animated)")),
        _camera(rng),
        *scene,
        *_light_sweep(rng),
        *_motes(rng),
        xmlns="http://www.w3.org/2000/svg",
        width=WIDTH,
        height=HEIGHT,
        viewBox=f"0 {top:.0f} {WIDTH} {HEIGHT}",
        preserveAspectRatio="xMidYMid slice",  # covers whatever box the player gives it
        role="img",
    )
    return root.encode()


def _push_in(width: float, height: float) -> str:
    """The root viewBox closing in on the middle by a tenth and back (a portrait's camera)."""
    return _viewbox_loop(
        f"0 0 {width} {height}",
        f"{width * 0.05:.1f} {height * 0.05:.1f} {width * 0.9:.1f} {height * 0.9:.1f}",
    )


def tall_poster(slug: str, subject: str) -> bytes:
    """A short's animated poster, 9:16: its thumbnail's portrait composition (apps.media
    thumbnails, the subject centred, no words) with the camera, light and motes of a poster."""
    rng = seeded_random(slug)
    scene = SCENES[check_subject(subject)](rng)
    width, height = thumbnails.TALL
    root = el(
        "svg",
        el("title", escape(f"{subject} {slug} (animated, portrait)")),
        _push_in(width, height),
        *thumbnails.portrait(scene, (height - width) / 2),
        *_light_sweep(rng),
        *_motes(rng),
        xmlns="http://www.w3.org/2000/svg",
        width=width,
        height=height,
        viewBox=f"0 0 {width} {height}",
        preserveAspectRatio="xMidYMid slice",
        role="img",
    )
    return root.encode()


@functools.lru_cache(maxsize=POSTERS_KEPT)
def drawn_poster(subject: str, slug: str, tall: bool = False) -> images.Image:
    """The poster of `slug` showing `subject` (one of pictures.SUBJECTS), 9:16 when `tall`,
    with its ETag."""
    return images.tagged(tall_poster(slug, subject) if tall else poster(slug, subject))
