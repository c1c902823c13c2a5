"""Covers: square album and playlist artwork, the way streaming services draw their own —
a bold two-colour gradient, a few large shapes, and (in most styles) the title set in big type.

The title comes from the slug itself ("late-night-jazz" → "LATE NIGHT JAZZ"), so the URL alone
is enough to draw the cover again, like every other generated image.
"""

from __future__ import annotations

import math
import random

from apps.media import palette
from apps.media.svg import document, el, linear_gradient, text

SIZE = 300
LINE_CHARACTERS = 11  # wrap the title at about this many characters a line
MAX_LINES = 3


def cover(rng: random.Random, slug: str) -> bytes:
    hue = rng.uniform(0, 360)
    style = rng.choice((_circles, _stripes, _waves, _blocks))
    parts = [
        el("defs", linear_gradient("bg", _gradient(rng, hue))),
        el("rect", width=SIZE, height=SIZE, fill="url(#bg)"),
        *style(rng, hue),
    ]
    if rng.random() < 0.75:
        parts += _title(rng, slug)
    return document(SIZE, SIZE, f"Cover {slug}", *parts)


def _gradient(rng: random.Random, hue: float) -> list[tuple[float, str]]:
    second = hue + rng.choice((40, 70, 150, 200))
    return [
        (0, palette.hsl(hue, 0.75, rng.uniform(0.38, 0.55))),
        (1, palette.hsl(second, 0.7, rng.uniform(0.16, 0.3))),
    ]


def _circles(rng: random.Random, hue: float) -> list[str]:
    return [
        el(
            "circle",
            cx=rng.uniform(0, SIZE),
            cy=rng.uniform(0, SIZE),
            r=rng.uniform(40, 140),
            fill=palette.hsl(hue + rng.uniform(-60, 60), 0.8, rng.uniform(0.45, 0.7)),
            opacity=round(rng.uniform(0.35, 0.8), 2),
        )
        for _ in range(rng.randint(2, 4))
    ]


def _stripes(rng: random.Random, hue: float) -> list[str]:
    angle = rng.choice((-30, -15, 15, 30, 45))
    colour = palette.hsl(hue + 180, 0.7, 0.6)
    bands = [
        el(
            "rect",
            x=-SIZE + i * 48,
            y=-SIZE,
            width=rng.uniform(10, 28),
            height=SIZE * 3,
            fill=colour,
            opacity=0.35,
        )
        for i in range(rng.randint(6, 9))
    ]
    return [el("g", *bands, transform=f"rotate({angle} {SIZE / 2} {SIZE / 2})")]


def _waves(rng: random.Random, hue: float) -> list[str]:
    shapes = []
    for i in range(3):
        phase, base = rng.uniform(0, 6.28), SIZE * (0.55 + 0.15 * i)
        points = " ".join(
            f"{x},{base - 18 * math.sin(x / SIZE * 2 * math.pi * 1.5 + phase):.1f}"
            for x in range(0, SIZE + 1, 15)
        )
        shapes.append(
            el(
                "polygon",
                points=f"0,{SIZE} {points} {SIZE},{SIZE}",
                fill=palette.hsl(hue + 25 * i, 0.65, 0.55 - 0.12 * i),
                opacity=0.8,
            )
        )
    return shapes


def _blocks(rng: random.Random, hue: float) -> list[str]:
    return [
        el(
            "rect",
            x=rng.uniform(-20, SIZE - 60),
            y=rng.uniform(-20, SIZE - 60),
            width=rng.uniform(60, 160),
            height=rng.uniform(60, 160),
            fill=palette.hsl(hue + rng.choice((30, 180, 210)), 0.75, rng.uniform(0.45, 0.65)),
            opacity=0.7,
            transform=f"rotate({rng.choice((0, 12, -12, 45))} {SIZE / 2} {SIZE / 2})",
        )
        for _ in range(rng.randint(2, 3))
    ]


def title_lines(slug: str) -> list[str]:
    """The slug's words in capitals, wrapped to at most MAX_LINES short lines."""
    lines: list[str] = []
    for word in slug.upper().split("-"):
        if lines and len(lines[-1]) + 1 + len(word) <= LINE_CHARACTERS:
            lines[-1] += " " + word
        else:
            lines.append(word)
    return lines[:MAX_LINES]


def _title(rng: random.Random, slug: str) -> list[str]:
    lines = title_lines(slug)
    longest = max(len(line) for line in lines)
    size = max(24, min(56, int(SIZE * 0.9 / max(longest, 1) * 1.3)))
    top = rng.choice((True, False))
    y0 = 24 + size if top else SIZE - 24 - size * (len(lines) - 1) * 1.05
    return [
        text(
            line,
            x=22,
            y=round(y0 + i * size * 1.05, 1),
            fill="#ffffff",
            font_family="Helvetica, Arial, sans-serif",
            font_weight=800,
            font_size=size,
            letter_spacing=-1,
        )
        for i, line in enumerate(lines)
    ]
