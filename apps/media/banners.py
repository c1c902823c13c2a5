"""Banners: a wide cover image behind a profile — layered hills or waves under a gradient sky,
or a soft geometric pattern — in one colour family per seed."""

from __future__ import annotations

import math
import random

from apps.media import palette
from apps.media.svg import document, el, linear_gradient

WIDTH, HEIGHT = 1200, 300


def banner(rng: random.Random, slug: str) -> bytes:
    draw = rng.choice((_hills, _hills, _waves, _pattern))
    return document(WIDTH, HEIGHT, f"Banner {slug}", *draw(rng), fit="slice")


def _ridge(rng: random.Random, base: float, amplitude: float, colour: str) -> str:
    """A filled band whose top edge is a smooth sum of two sine waves."""
    phase, phase2 = rng.uniform(0, 6.28), rng.uniform(0, 6.28)
    k1, k2 = rng.uniform(1.2, 2.6), rng.uniform(3, 6)
    points = []
    for i in range(41):
        x = WIDTH * i / 40
        y = base - amplitude * (
            0.7 * math.sin(k1 * x / WIDTH * math.pi + phase)
            + 0.3 * math.sin(k2 * x / WIDTH * math.pi + phase2)
        )
        points.append(f"{x:.0f},{y:.1f}")
    return el(
        "polygon", points=f"0,{HEIGHT} " + " ".join(points) + f" {WIDTH},{HEIGHT}", fill=colour
    )


def _sky(rng: random.Random, hue: float) -> list[str]:
    top = palette.hsl(hue, 0.55, 0.72)
    bottom = palette.hsl(hue + rng.uniform(20, 50), 0.65, 0.9)
    return [
        el("defs", linear_gradient("sky", [(0, top), (1, bottom)])),
        el("rect", width=WIDTH, height=HEIGHT, fill="url(#sky)"),
    ]


def _hills(rng: random.Random) -> list[str]:
    hue = rng.uniform(0, 360)
    parts = _sky(rng, hue)
    parts.append(el("circle", cx=rng.uniform(150, 1050), cy=rng.uniform(70, 120), r=rng.uniform(34, 50),
                    fill=palette.hsl(hue + 40, 0.9, 0.93), opacity=0.9))  # fmt: skip
    layers = 4
    ground_hue = hue + rng.choice((-140, -100, 160, 180))
    for i in range(layers):
        colour = palette.hsl(ground_hue + i * 6, 0.35 + i * 0.05, 0.7 - i * 0.14)
        parts.append(_ridge(rng, 150 + i * 40, 40 - i * 5, colour))
    return parts


def _waves(rng: random.Random) -> list[str]:
    hue = rng.uniform(0, 360)
    parts = _sky(rng, hue)
    for i in range(5):
        colour = palette.hsl(hue + 10 * i, 0.6, 0.78 - i * 0.1)
        parts.append(_ridge(rng, 120 + i * 38, 22, colour))
    return parts


def _pattern(rng: random.Random) -> list[str]:
    hue = rng.uniform(0, 360)
    ground = palette.hsl(hue, 0.5, 0.35)
    parts = [el("rect", width=WIDTH, height=HEIGHT, fill=ground)]
    for _ in range(26):
        r = rng.uniform(20, 140)
        parts.append(el("circle", cx=rng.uniform(0, WIDTH), cy=rng.uniform(0, HEIGHT), r=r,
                        fill=palette.hsl(hue + rng.uniform(-40, 40), 0.6, rng.uniform(0.45, 0.75)),
                        opacity=round(rng.uniform(0.25, 0.6), 2)))  # fmt: skip
    return parts
