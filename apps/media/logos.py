"""Logos and team icons: a rounded square in brand colours carrying a geometric mark (rings,
bars, peaks, a hexagon, chevrons, a pinwheel…) or, for about a quarter of names, initials."""

from __future__ import annotations

import math
import random

from apps.media import palette
from apps.media.svg import document, el, path, text

SIZE = 128
C = SIZE / 2


def initials(slug: str) -> str:
    """ "acme-robotics" → "AR"; "globex" → "G"."""
    words = [word for word in slug.split("-") if word]
    return "".join(word[0] for word in words[:2]).upper()


def mark(rng: random.Random, slug: str) -> bytes:
    ground, ink = rng.choice(palette.BRAND_PAIRS)
    accent = palette.mix(ink, ground, 0.45)
    draw = rng.choice(MARKS)
    figure = _initials(slug, ink) if rng.random() < 0.25 else draw(rng, ink, accent)
    square = el("rect", width=SIZE, height=SIZE, rx=26, fill=ground)
    edge = (
        el("rect", x=1, y=1, width=SIZE - 2, height=SIZE - 2, rx=25, fill="none",
           stroke="#e2e8f0", stroke_width=2)
        if palette.lightness(ground) > 0.9
        else ""
    )  # fmt: skip
    return document(SIZE, SIZE, f"Logo {slug}", square, edge, figure)


def _initials(slug: str, ink: str) -> str:
    letters = initials(slug)
    return text(
        letters,
        x=C,
        y=C + (20 if len(letters) == 2 else 24),
        text_anchor="middle",
        font_family="system-ui, 'Segoe UI', Helvetica, Arial, sans-serif",
        font_size=56 if len(letters) == 2 else 68,
        font_weight=700,
        letter_spacing=-2,
        fill=ink,
    )


def _ring(rng: random.Random, ink: str, accent: str) -> str:
    return el(
        "g",
        el("circle", cx=C, cy=C, r=32, fill="none", stroke=ink, stroke_width=14),
        el("circle", cx=C + 32 * math.cos(rng.uniform(0, 6.28)),
           cy=C + 32 * math.sin(rng.uniform(0, 6.28)), r=10, fill=accent),
    )  # fmt: skip


def _bars(rng: random.Random, ink: str, accent: str) -> str:
    heights = sorted(rng.uniform(26, 64) for _ in range(3))
    return el("g", *(
        el("rect", x=30 + i * 26, y=96 - h, width=18, height=h, rx=5, fill=ink if i != 1 else accent)
        for i, h in enumerate(heights)
    ))  # fmt: skip


def _peaks(rng: random.Random, ink: str, accent: str) -> str:
    return el(
        "g",
        path("M", 22, 94, "L", 54, 40, "L", 86, 94, "Z", fill=accent),
        path("M", 50, 94, "L", 78, 48, "L", 106, 94, "Z", fill=ink),
        el("circle", cx=92, cy=34, r=9, fill=ink) if rng.random() < 0.5 else "",
    )


def _hexagon(rng: random.Random, ink: str, accent: str) -> str:
    points = " ".join(
        f"{C + 38 * math.cos(math.radians(60 * i + 30)):.1f},{C + 38 * math.sin(math.radians(60 * i + 30)):.1f}"
        for i in range(6)
    )
    return el(
        "g",
        el("polygon", points=points, fill="none", stroke=ink, stroke_width=11, stroke_linejoin="round"),
        el("circle", cx=C, cy=C, r=12, fill=accent),
    )  # fmt: skip


def _venn(rng: random.Random, ink: str, accent: str) -> str:
    return el(
        "g",
        el("circle", cx=C - 14, cy=C, r=28, fill=accent),
        el("circle", cx=C + 14, cy=C, r=28, fill=ink, opacity=0.85),
    )


def _chevrons(rng: random.Random, ink: str, accent: str) -> str:
    def chevron(y: float, colour: str) -> str:
        return path("M", 32, y + 16, "L", C, y - 8, "L", 96, y + 16, fill="none", stroke=colour,
                    stroke_width=14, stroke_linecap="round", stroke_linejoin="round")  # fmt: skip

    return el("g", chevron(48, ink), chevron(76, accent))


def _pinwheel(rng: random.Random, ink: str, accent: str) -> str:
    r = 30
    blades = []
    for i, (sx, sy) in enumerate(((1, -1), (1, 1), (-1, 1), (-1, -1))):
        corner_x, corner_y = C + sx * r, C + sy * r
        blades.append(path("M", C, C, "L", corner_x, C, "A", r, r, 0, 0, 1 if sx * sy > 0 else 0,
                           C, corner_y, "Z", fill=ink if i % 2 == 0 else accent,
                           transform=f"rotate({rng.choice((0, 15, 30))} {C} {C})"))  # fmt: skip
    return el("g", *blades)


def _leaf(rng: random.Random, ink: str, accent: str) -> str:
    return el(
        "g",
        path("M", 34, 94, "C", 30, 50, 60, 30, 96, 30, "C", 98, 70, 74, 98, 34, 94, "Z", fill=ink),
        path("M", 40, 88, "Q", 62, 62, 86, 42, fill="none", stroke=accent, stroke_width=5,
             stroke_linecap="round"),
    )  # fmt: skip


def _spark(rng: random.Random, ink: str, accent: str) -> str:
    star = path("M", C, 24, "C", C + 4, 54, C + 10, 60, 104, C, "C", C + 10, 68, C + 4, 74, C, 104,
                "C", C - 4, 74, C - 10, 68, 24, C, "C", C - 10, 60, C - 4, 54, C, 24, "Z", fill=ink)  # fmt: skip
    return el("g", star, el("circle", cx=96, cy=34, r=8, fill=accent))


def _waves(rng: random.Random, ink: str, accent: str) -> str:
    lines = []
    for i, y in enumerate((46, 64, 82)):
        lines.append(path("M", 28, y, "q", 12, -12, 24, 0, "t", 24, 0, "t", 24, 0, "t", 24, 0,
                          fill="none", stroke=ink if i != 1 else accent, stroke_width=9,
                          stroke_linecap="round"))  # fmt: skip
    return el("g", *lines)


def _blocks(rng: random.Random, ink: str, accent: str) -> str:
    odd = rng.randrange(4)
    return el("g", *(
        el("rect", x=32 + (i % 2) * 34, y=32 + (i // 2) * 34, width=28, height=28,
           rx=14 if i == odd else 7, fill=accent if i == odd else ink)
        for i in range(4)
    ))  # fmt: skip


def _orbit(rng: random.Random, ink: str, accent: str) -> str:
    return el(
        "g",
        el("circle", cx=C, cy=C, r=16, fill=ink),
        el("ellipse", cx=C, cy=C, rx=42, ry=16, fill="none", stroke=accent, stroke_width=6,
           transform=f"rotate({rng.choice((-30, -20, 20, 30))} {C} {C})"),
    )  # fmt: skip


MARKS = (
    _ring, _bars, _peaks, _hexagon, _venn, _chevrons, _pinwheel, _leaf, _spark, _waves,
    _blocks, _orbit,
)  # fmt: skip
