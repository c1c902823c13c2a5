"""Pictures: photo-like flat illustrations for image attachments and posts, one scene per subject
(a landscape, a city skyline, a plate of food, a desk, a whiteboard, a chart, an app screenshot,
a pet, a product shot, a group of people, abstract shapes). 480×320 (3:2), covering any box."""

from __future__ import annotations

import itertools
import math
import random
from collections.abc import Callable

from apps.media import palette
from apps.media.faces import portrait_figure
from apps.media.svg import document, el, linear_gradient, path

WIDTH, HEIGHT = 480, 320
Scene = Callable[[random.Random], list[str]]


def check_subject(subject: str) -> str:
    """`subject` if a scene is drawn for it; otherwise ValueError naming the allowed ones."""
    if subject not in SCENES:
        raise ValueError(f"picture subject {subject!r}: allowed {', '.join(SCENES)}")
    return subject


def picture(rng: random.Random, slug: str, subject: str) -> bytes:
    return document(
        WIDTH, HEIGHT, f"{subject} {slug}", *SCENES[check_subject(subject)](rng), fit="slice"
    )


def _gradient_sky(rng: random.Random, top: str, bottom: str, gradient_id: str = "sky") -> list[str]:
    return [
        el("defs", linear_gradient(gradient_id, [(0, top), (1, bottom)])),
        el("rect", width=WIDTH, height=HEIGHT, fill=f"url(#{gradient_id})"),
    ]


def _hill(rng: random.Random, base: float, amplitude: float, colour: str) -> str:
    phase, k = rng.uniform(0, 6.28), rng.uniform(1.2, 2.4)
    points = " ".join(
        f"{WIDTH * i / 24:.0f},{base - amplitude * math.sin(k * math.pi * i / 24 + phase):.1f}"
        for i in range(25)
    )
    return el("polygon", points=f"0,{HEIGHT} {points} {WIDTH},{HEIGHT}", fill=colour)


def _tree(x: float, ground: float, height: float, leaves: str, kind: str) -> str:
    trunk = el("rect", x=x - height * 0.05, y=ground - height * 0.4, width=height * 0.1,
               height=height * 0.4, fill="#6b4423")  # fmt: skip
    if kind == "pine":
        crown = path("M", x, ground - height, "L", x + height * 0.28, ground - height * 0.3,
                     "L", x - height * 0.28, ground - height * 0.3, "Z", fill=leaves)  # fmt: skip
    else:
        crown = el("circle", cx=x, cy=ground - height * 0.62, r=height * 0.3, fill=leaves)
    return el("g", trunk, crown)


def _landscape(rng: random.Random) -> list[str]:
    evening = rng.random() < 0.3
    parts = _gradient_sky(
        rng,
        "#f59e8b" if evening else palette.hsl(rng.uniform(195, 215), 0.7, 0.62),
        "#fde2b8" if evening else "#e0f2fe",
    )
    sun_y = rng.uniform(90, 130) if evening else rng.uniform(50, 90)
    parts.append(
        el(
            "circle",
            cx=rng.uniform(80, 400),
            cy=sun_y,
            r=26,
            fill="#fff7d6" if not evening else "#fde68a",
        )
    )
    for _ in range(rng.randint(1, 3)):  # clouds
        cx, cy = rng.uniform(40, 440), rng.uniform(30, 100)
        parts.append(el("g", *(el("ellipse", cx=cx + dx, cy=cy + dy, rx=rx, ry=ry, fill="#ffffff", opacity=0.9)
                              for dx, dy, rx, ry in ((0, 0, 30, 12), (18, -8, 18, 12), (-14, -5, 14, 9)))))  # fmt: skip
    mountain = "#94a3b8" if not evening else "#b07a8a"
    peak = rng.uniform(140, 340)
    parts.append(
        path(
            "M",
            peak - 220,
            230,
            "L",
            peak,
            rng.uniform(80, 110),
            "L",
            peak + 220,
            230,
            "Z",
            fill=mountain,
        )
    )
    parts.append(path("M", peak - 34, 130, "L", peak, rng.uniform(80, 110), "L", peak + 34, 130, "Z", fill="#f8fafc", opacity=0.85))  # fmt: skip
    greens = ("#86c06c", "#5fa35a", "#3f7f47") if not evening else ("#7c8f5a", "#566b46", "#3a4a34")
    parts.append(_hill(rng, 225, 18, greens[0]))
    parts.append(_hill(rng, 260, 14, greens[1]))
    for _ in range(rng.randint(3, 7)):
        x = rng.uniform(10, 470)
        parts.append(
            _tree(
                x,
                rng.uniform(262, 300),
                rng.uniform(40, 70),
                greens[2],
                rng.choice(("pine", "round")),
            )
        )
    if rng.random() < 0.5:  # a lake
        parts.append(
            el(
                "ellipse",
                cx=rng.uniform(120, 360),
                cy=300,
                rx=130,
                ry=18,
                fill="#7dd3fc",
                opacity=0.9,
            )
        )
    return parts


def _city(rng: random.Random) -> list[str]:
    night = rng.random() < 0.4
    parts = _gradient_sky(rng, "#1e1b4b" if night else "#7dd3fc", "#6d28d9" if night else "#e0f2fe")
    if night:
        parts.append(el("circle", cx=rng.uniform(60, 420), cy=60, r=18, fill="#fef9c3"))
    x = -10.0
    for layer, (shade, lit) in enumerate(((0.55, 0.2), (0.0, 0.6))):
        x = -10.0
        while x < WIDTH:
            w = rng.uniform(38, 70)
            h = rng.uniform(90, 220) - layer * 30
            base = (
                "#334155" if night else palette.hsl(rng.uniform(200, 230), 0.15, 0.45 + shade * 0.4)
            )
            if layer == 0:
                base = palette.mix(base, "#94a3b8" if not night else "#312e81", 0.5)
            top = HEIGHT - 40 - h
            parts.append(el("rect", x=x, y=top, width=w, height=h + 40, fill=base))
            if layer == 1:
                window = "#fde68a" if night else "#e0f2fe"
                for wy in range(int(top + 10), HEIGHT - 50, 16):
                    for wx in range(int(x + 6), int(x + w - 8), 12):
                        if rng.random() < (lit if night else 0.85):
                            parts.append(
                                el("rect", x=wx, y=wy, width=6, height=9, fill=window, opacity=0.9)
                            )
            x += w + rng.uniform(2, 10)
    parts.append(
        el("rect", y=HEIGHT - 40, width=WIDTH, height=40, fill="#1f2937" if night else "#475569")
    )
    parts.append(
        path(
            "M",
            0,
            HEIGHT - 20,
            "H",
            WIDTH,
            stroke="#facc15",
            stroke_width=3,
            stroke_dasharray="18 14",
        )
    )
    return parts


def _food(rng: random.Random) -> list[str]:
    table = rng.choice(("#c08a5b", "#a16f47", "#e7d7c1", "#d6c3a5", "#8b5e3c"))
    parts = [el("rect", width=WIDTH, height=HEIGHT, fill=table)]
    for y in range(0, HEIGHT, 40):  # planks
        parts.append(path("M", 0, y, "H", WIDTH, stroke=palette.shade(table, 0.12), stroke_width=2))
    parts.append(
        el(
            "rect",
            x=300,
            y=-20,
            width=170,
            height=110,
            rx=8,
            fill="#f1f5f9",
            transform="rotate(12 380 40)",
        )
    )  # napkin
    parts.append(el("ellipse", cx=220, cy=170, rx=128, ry=118, fill="#000000", opacity=0.12))
    parts.append(el("circle", cx=212, cy=160, r=120, fill="#ffffff"))
    parts.append(
        el("circle", cx=212, cy=160, r=92, fill="#f8fafc", stroke="#e2e8f0", stroke_width=3)
    )
    dish = rng.choice(("salad", "pasta", "bowl"))
    if dish == "salad":
        for _ in range(16):
            a, d = rng.uniform(0, 6.28), rng.uniform(0, 60)
            parts.append(el("ellipse", cx=212 + d * math.cos(a), cy=160 + d * math.sin(a), rx=22, ry=12,
                            fill=rng.choice(("#65a30d", "#84cc16", "#4d7c0f")),
                            transform=f"rotate({rng.uniform(0, 180):.0f} {212 + d * math.cos(a):.0f} {160 + d * math.sin(a):.0f})"))  # fmt: skip
        for _ in range(6):
            a, d = rng.uniform(0, 6.28), rng.uniform(10, 55)
            parts.append(
                el(
                    "circle",
                    cx=212 + d * math.cos(a),
                    cy=160 + d * math.sin(a),
                    r=10,
                    fill="#ef4444",
                )
            )
    elif dish == "pasta":
        for i in range(14):
            parts.append(path("M", 150 + i * 8, 130 + (i % 3) * 6, "q", 20, 30, 40, 0, "t", 40, 10,
                              fill="none", stroke="#fbbf24", stroke_width=6, stroke_linecap="round"))  # fmt: skip
        parts.append(el("ellipse", cx=212, cy=150, rx=50, ry=28, fill="#dc2626", opacity=0.85))
        for dx in (-20, 10, 30):
            parts.append(el("circle", cx=212 + dx, cy=150 - dx / 3, r=5, fill="#16a34a"))
    else:
        parts.append(el("circle", cx=212, cy=160, r=70, fill="#f59e0b"))
        for dx, dy, colour in (
            (-25, -20, "#fef3c7"),
            (20, -25, "#16a34a"),
            (25, 20, "#b91c1c"),
            (-20, 25, "#7c2d12"),
        ):
            parts.append(el("circle", cx=212 + dx, cy=160 + dy, r=20, fill=colour))
    parts.append(
        el("rect", x=370, y=110, width=10, height=170, rx=5, fill="#cbd5e1")
    )  # fork handle
    parts.append(el("rect", x=400, y=110, width=10, height=170, rx=5, fill="#cbd5e1"))
    parts.append(el("circle", cx=60, cy=60, r=40, fill="#ffffff", opacity=0.9))  # a glass
    parts.append(
        el(
            "circle",
            cx=60,
            cy=60,
            r=30,
            fill=rng.choice(("#fca5a5", "#fde68a", "#bae6fd")),
            opacity=0.8,
        )
    )
    return parts


def _plant(x: float, y: float, scale: float = 1.0) -> str:
    leaves = [
        el("ellipse", cx=x + dx * scale, cy=y - 26 * scale + dy * scale, rx=9 * scale, ry=20 * scale,
           fill="#22c55e" if i % 2 else "#15803d", transform=f"rotate({angle} {x + dx * scale:.0f} {y - 26 * scale + dy * scale:.0f})")
        for i, (dx, dy, angle) in enumerate(((-12, 0, -30), (12, 0, 30), (0, -8, 0), (-6, 4, -60), (6, 4, 60)))
    ]  # fmt: skip
    pot = path("M", x - 16 * scale, y - 10 * scale, "H", x + 16 * scale, "L", x + 12 * scale, y + 14 * scale,
               "H", x - 12 * scale, "Z", fill="#c2410c")  # fmt: skip
    return el("g", *leaves, pot)


def _office(rng: random.Random) -> list[str]:
    """A desk against a wall: a monitor or a laptop, a plant, a mug, a window or a shelf."""
    wall = rng.choice(("#e0e7ff", "#fef3c7", "#dcfce7", "#f1f5f9", "#fae8ff", "#ffe4e6"))
    desk = rng.choice(("#a16207", "#92400e", "#d6d3d1", "#f5f5f4", "#78716c"))
    screen = palette.hsl(rng.uniform(190, 260), 0.6, 0.55)
    left = rng.random() < 0.5  # which side the window (or shelf) and the plant go
    side_x, plant_x = (30, 410) if left else (330, 70)
    parts = [el("rect", width=WIDTH, height=HEIGHT, fill=wall)]
    if rng.random() < 0.6:  # a window with a view of the sky
        parts += [
            el("rect", x=side_x, y=30, width=120, height=90, rx=4, fill="#bae6fd",
               stroke="#ffffff", stroke_width=6),
            path("M", side_x + 60, 30, "V", 120, "M", side_x, 75, "H", side_x + 120,
                 stroke="#ffffff", stroke_width=4),
        ]  # fmt: skip
    else:  # a shelf of books
        parts.append(
            el("rect", x=side_x, y=110, width=120, height=8, fill=palette.shade(desk, 0.2))
        )
        x = side_x + 6
        while x < side_x + 110:
            width, height = rng.uniform(8, 14), rng.uniform(34, 52)
            parts.append(el("rect", x=x, y=110 - height, width=width, height=height, rx=1,
                            fill=palette.hsl(rng.uniform(0, 360), 0.5, 0.5)))  # fmt: skip
            x += width + 2
    poster_x = 350 - side_x + 10 if left else 40  # the other wall: a framed picture
    parts += [
        el("rect", x=poster_x + 60, y=36, width=84, height=60, rx=3, fill="#ffffff"),
        el("rect", x=poster_x + 66, y=42, width=72, height=48, fill=palette.hsl(rng.uniform(0, 360), 0.5, 0.65)),
        el("rect", y=230, width=WIDTH, height=90, fill=desk),
        el("rect", y=226, width=WIDTH, height=10, fill=palette.shade(desk, 0.15)),
    ]  # fmt: skip
    lines = [
        el("rect", x=0, y=i * 20, width=rng.uniform(50, 130), height=8, rx=4, fill="#ffffff",
           opacity=0.8)
        for i in range(4)
    ]  # fmt: skip
    if rng.random() < 0.6:  # a monitor on a stand, keyboard and mouse
        parts += [
            el("rect", x=150, y=90, width=180, height=118, rx=8, fill="#1f2937"),
            el("rect", x=158, y=98, width=164, height=100, rx=3, fill=screen),
            el("g", *lines, transform="translate(168 110)"),
            el("rect", x=228, y=208, width=24, height=20, fill="#374151"),
            el("rect", x=200, y=222, width=80, height=8, rx=3, fill="#374151"),
            el("rect", x=170, y=244, width=140, height=16, rx=4, fill="#e5e7eb"),
            el("rect", x=330, y=246, width=20, height=28, rx=10, fill="#e5e7eb"),
        ]  # fmt: skip
    else:  # an open laptop
        parts += [
            el("rect", x=160, y=120, width=160, height=104, rx=8, fill="#cbd5e1"),
            el("rect", x=168, y=128, width=144, height=90, rx=3, fill=screen),
            el("g", *lines, transform="translate(178 140) scale(0.85)"),
            path("M", 136, 232, "L", 344, 232, "L", 330, 224, "L", 150, 224, "Z", fill="#94a3b8"),
        ]  # fmt: skip
    parts.append(_plant(plant_x, 214, 1.3))
    mug_x = 110 if left else 360
    parts += [
        el("rect", x=mug_x, y=196, width=30, height=34, rx=4, fill=rng.choice(("#ffffff", "#f87171", "#60a5fa"))),
        path("M", mug_x + 30, 204, "q", 12, 0, 12, 10, "t", -12, 10, fill="none", stroke="#ffffff",
             stroke_width=5),
    ]  # fmt: skip
    return parts


def _whiteboard(rng: random.Random) -> list[str]:
    parts = [el("rect", width=WIDTH, height=HEIGHT, fill="#e7e5e4")]
    parts.append(
        el(
            "rect",
            x=24,
            y=20,
            width=432,
            height=270,
            rx=6,
            fill="#ffffff",
            stroke="#9ca3af",
            stroke_width=8,
        )
    )
    parts.append(el("rect", x=60, y=290, width=360, height=10, rx=3, fill="#9ca3af"))
    notes = ("#fde047", "#f9a8d4", "#86efac", "#93c5fd", "#fdba74")
    positions = []
    for row in range(2):  # row by row, so neighbours in the list sit side by side
        for column in range(4):
            if rng.random() < 0.8:
                x, y = 50 + column * 102 + rng.uniform(-6, 6), 48 + row * 110 + rng.uniform(-6, 6)
                positions.append((x, y))
                colour = rng.choice(notes)
                parts.append(el("rect", x=x, y=y, width=64, height=64, fill=colour,
                                transform=f"rotate({rng.uniform(-5, 5):.1f} {x + 32:.0f} {y + 32:.0f})"))  # fmt: skip
                for line in range(3):
                    parts.append(path("M", x + 8, y + 16 + line * 14, "h", rng.uniform(24, 46), stroke="#374151",
                                      stroke_width=2.5, stroke_linecap="round", opacity=0.7))  # fmt: skip
    marker = rng.choice(("#2563eb", "#dc2626", "#111827"))
    for (x1, y1), (x2, y2) in itertools.pairwise(positions):
        if abs(y1 - y2) < 20 and x2 - x1 < 130 and rng.random() < 0.8:
            parts.append(path("M", x1 + 68, y1 + 32, "Q", (x1 + x2) / 2 + 32, y1 + 4, x2 - 6, y2 + 32, fill="none",
                              stroke=marker, stroke_width=3, stroke_linecap="round"))  # fmt: skip
            parts.append(path("M", x2 - 14, y2 + 24, "L", x2 - 5, y2 + 32, "L", x2 - 15, y2 + 38, fill="none",
                              stroke=marker, stroke_width=3, stroke_linecap="round"))  # fmt: skip
    return parts


def _chart(rng: random.Random) -> list[str]:
    accent = palette.hsl(rng.uniform(0, 360), 0.65, 0.5)
    parts = [el("rect", width=WIDTH, height=HEIGHT, fill="#f1f5f9")]
    parts.append(
        el(
            "rect",
            x=24,
            y=20,
            width=432,
            height=280,
            rx=12,
            fill="#ffffff",
            stroke="#e2e8f0",
            stroke_width=2,
        )
    )
    parts.append(el("rect", x=48, y=40, width=140, height=12, rx=6, fill="#334155"))
    parts.append(el("rect", x=48, y=60, width=90, height=8, rx=4, fill="#94a3b8"))
    for i in range(5):
        y = 100 + i * 40
        parts.append(path("M", 60, y, "H", 432, stroke="#e2e8f0", stroke_width=1.5))
    values = [rng.uniform(0.2, 1.0) for _ in range(8)]
    if rng.random() < 0.5:
        for i, v in enumerate(values):
            h = v * 150
            parts.append(el("rect", x=72 + i * 45, y=260 - h, width=28, height=h, rx=4,
                            fill=accent if i != len(values) - 1 else palette.shade(accent, 0.3)))  # fmt: skip
    else:
        points = [(64 + i * 52, 260 - v * 150) for i, v in enumerate(values)]
        line = " ".join(f"{x:.0f},{y:.0f}" for x, y in points)
        parts.append(
            el(
                "polygon",
                points=f"64,260 {line} {points[-1][0]:.0f},260",
                fill=accent,
                opacity=0.15,
            )
        )
        parts.append(
            el(
                "polyline",
                points=line,
                fill="none",
                stroke=accent,
                stroke_width=4,
                stroke_linejoin="round",
            )
        )
        parts += [
            el("circle", cx=x, cy=y, r=5, fill="#ffffff", stroke=accent, stroke_width=3)
            for x, y in points
        ]
    parts.append(path("M", 60, 260, "H", 432, stroke="#94a3b8", stroke_width=2))
    return parts


def _screenshot(rng: random.Random) -> list[str]:
    accent = palette.hsl(rng.uniform(0, 360), 0.6, 0.5)
    parts = [
        el("rect", width=WIDTH, height=HEIGHT, fill=palette.hsl(rng.uniform(0, 360), 0.3, 0.85))
    ]
    parts.append(el("rect", x=20, y=18, width=440, height=290, rx=10, fill="#ffffff"))
    parts.append(path("M", 20, 28, "a", 10, 10, 0, 0, 1, 10, -10, "H", 450, "a", 10, 10, 0, 0, 1, 10, 10, "V", 44, "H", 20, "Z", fill="#e2e8f0"))  # fmt: skip
    for i, colour in enumerate(("#ef4444", "#f59e0b", "#22c55e")):
        parts.append(el("circle", cx=36 + i * 14, cy=31, r=4.5, fill=colour))
    parts.append(el("rect", x=100, y=25, width=260, height=12, rx=6, fill="#ffffff"))
    parts.append(el("rect", x=20, y=44, width=440, height=30, fill=accent))
    parts.append(el("rect", x=34, y=54, width=60, height=10, rx=5, fill="#ffffff", opacity=0.9))
    parts.append(el("rect", x=20, y=74, width=96, height=234, fill="#f8fafc"))
    for i in range(6):
        parts.append(el("rect", x=32, y=88 + i * 24, width=rng.uniform(40, 70), height=8, rx=4,
                        fill=accent if i == 0 else "#cbd5e1"))  # fmt: skip
    for row in range(2):
        for column in range(3):
            x, y = 132 + column * 108, 88 + row * 104
            parts.append(
                el("rect", x=x, y=y, width=96, height=92, rx=6, fill="#f1f5f9", stroke="#e2e8f0")
            )
            parts.append(el("rect", x=x + 8, y=y + 8, width=80, height=44, rx=4,
                            fill=palette.hsl(rng.uniform(0, 360), 0.5, 0.75)))  # fmt: skip
            parts.append(
                el(
                    "rect",
                    x=x + 8,
                    y=y + 60,
                    width=rng.uniform(40, 76),
                    height=7,
                    rx=3.5,
                    fill="#64748b",
                )
            )
            parts.append(
                el(
                    "rect",
                    x=x + 8,
                    y=y + 74,
                    width=rng.uniform(24, 60),
                    height=6,
                    rx=3,
                    fill="#cbd5e1",
                )
            )
    return parts


def _pet(rng: random.Random) -> list[str]:
    backdrop = rng.choice(("#fde68a", "#bfdbfe", "#fbcfe8", "#bbf7d0", "#e9d5ff"))
    fur = rng.choice(("#f97316", "#78350f", "#1f2937", "#d6d3d1", "#a8a29e", "#fbbf24"))
    parts = [el("rect", width=WIDTH, height=HEIGHT, fill=backdrop)]
    parts.append(el("rect", y=250, width=WIDTH, height=70, fill=palette.shade(backdrop, 0.15)))
    parts.append(el("ellipse", cx=240, cy=270, rx=130, ry=16, fill="#000000", opacity=0.12))
    dark = palette.shade(fur, 0.3)
    if rng.random() < 0.5:  # a sitting cat
        parts += [
            path("M", 330, 260, "C", 420, 260, 420, 180, 380, 170, fill="none", stroke=fur, stroke_width=16, stroke_linecap="round"),
            el("ellipse", cx=240, cy=210, rx=80, ry=62, fill=fur),
            el("circle", cx=240, cy=120, r=56, fill=fur),
            path("M", 192, 100, "L", 196, 50, "L", 228, 76, "Z", fill=fur),
            path("M", 288, 100, "L", 284, 50, "L", 252, 76, "Z", fill=fur),
            path("M", 198, 90, "L", 200, 62, "L", 220, 78, "Z", fill="#fda4af"),
            path("M", 282, 90, "L", 280, 62, "L", 260, 78, "Z", fill="#fda4af"),
            el("ellipse", cx=218, cy=118, rx=8, ry=11, fill="#84cc16"),
            el("ellipse", cx=262, cy=118, rx=8, ry=11, fill="#84cc16"),
            el("ellipse", cx=218, cy=119, rx=3, ry=9, fill="#111827"),
            el("ellipse", cx=262, cy=119, rx=3, ry=9, fill="#111827"),
            path("M", 234, 138, "L", 246, 138, "L", 240, 145, "Z", fill="#f472b6"),
            path("M", 200, 146, "L", 170, 140, "M", 200, 152, "L", 170, 156, "M", 280, 146, "L", 310, 140,
                 "M", 280, 152, "L", 310, 156, stroke=dark, stroke_width=2),
            el("ellipse", cx=210, cy=266, rx=20, ry=10, fill=fur),
            el("ellipse", cx=270, cy=266, rx=20, ry=10, fill=fur),
        ]  # fmt: skip
    else:  # a dog
        parts += [
            el("ellipse", cx=240, cy=214, rx=78, ry=58, fill=fur),
            el("circle", cx=240, cy=124, r=54, fill=fur),
            el("ellipse", cx=186, cy=128, rx=18, ry=40, fill=dark, transform="rotate(20 186 128)"),
            el("ellipse", cx=294, cy=128, rx=18, ry=40, fill=dark, transform="rotate(-20 294 128)"),
            el("ellipse", cx=240, cy=150, rx=30, ry=24, fill=palette.shade(fur, -0.4)),
            el("circle", cx=220, cy=114, r=6, fill="#111827"),
            el("circle", cx=260, cy=114, r=6, fill="#111827"),
            el("ellipse", cx=240, cy=140, rx=10, ry=7, fill="#111827"),
            path("M", 240, 147, "v", 8, "M", 228, 156, "q", 12, 8, 24, 0, stroke="#111827", stroke_width=3, fill="none"),
            path("M", 232, 160, "q", 8, 16, 16, 0, fill="#fb7185"),
            el("ellipse", cx=208, cy=266, rx=20, ry=10, fill=fur),
            el("ellipse", cx=272, cy=266, rx=20, ry=10, fill=fur),
            el("rect", x=206, y=168, width=68, height=10, rx=5, fill="#dc2626"),
        ]  # fmt: skip
    return parts


def _product(rng: random.Random) -> list[str]:
    hue = rng.uniform(0, 360)
    parts = _gradient_sky(
        rng, palette.hsl(hue, 0.45, 0.86), palette.hsl(hue, 0.35, 0.7), "backdrop"
    )
    parts.append(el("ellipse", cx=240, cy=282, rx=150, ry=16, fill="#000000", opacity=0.15))
    body = rng.choice(("#111827", "#e5e7eb", "#1e3a8a", "#f8fafc"))
    device = rng.choice(("phone", "headphones", "watch"))
    if device == "phone":
        parts += [
            el("rect", x=176, y=34, width=128, height=246, rx=20, fill=body),
            el(
                "rect",
                x=184,
                y=44,
                width=112,
                height=226,
                rx=14,
                fill=palette.hsl(hue + 150, 0.6, 0.6),
            ),
            el("circle", cx=240, cy=120, r=34, fill="#ffffff", opacity=0.35),
            el("rect", x=220, y=50, width=40, height=8, rx=4, fill=body),
        ]
    elif device == "headphones":
        parts += [
            path("M", 150, 200, "C", 150, 50, 330, 50, 330, 200, fill="none", stroke=body, stroke_width=18, stroke_linecap="round"),
            el("rect", x=124, y=170, width=56, height=100, rx=24, fill=body),
            el("rect", x=300, y=170, width=56, height=100, rx=24, fill=body),
            el("rect", x=136, y=186, width=32, height=68, rx=14, fill=palette.hsl(hue + 150, 0.6, 0.55)),
            el("rect", x=312, y=186, width=32, height=68, rx=14, fill=palette.hsl(hue + 150, 0.6, 0.55)),
        ]  # fmt: skip
    else:
        parts += [
            el("rect", x=206, y=20, width=68, height=280, rx=22, fill=palette.hsl(hue + 180, 0.4, 0.4)),
            el("rect", x=180, y=100, width=120, height=130, rx=30, fill=body),
            el("rect", x=192, y=112, width=96, height=106, rx=22, fill="#0f172a"),
            el("circle", cx=240, cy=165, r=34, fill="none", stroke=palette.hsl(hue + 150, 0.7, 0.6), stroke_width=8),
            el("rect", x=300, y=150, width=8, height=26, rx=3, fill=body),
        ]  # fmt: skip
    return parts


def _people(rng: random.Random) -> list[str]:
    """A group photo: a back row and a front row of people, shoulders overlapping."""
    hue = rng.uniform(0, 360)
    parts = [el("rect", width=WIDTH, height=HEIGHT, fill=palette.hsl(hue, 0.4, 0.86))]
    parts.append(el("rect", x=rng.uniform(20, 300), y=30, width=160, height=110, rx=6,
                    fill=palette.hsl(hue + 30, 0.35, 0.93)))  # a window behind them  # fmt: skip
    back, front = rng.choice(((2, 3), (1, 2), (2, 2), (3, 3)))
    for count, scale, bottom in ((back, 1.35, 262), (front, 1.7, 344)):
        spacing = WIDTH / count
        for i in range(count):
            x = spacing * (i + 0.5) + rng.uniform(-12, 12)
            parts.append(portrait_figure(rng, x, bottom, scale))
    return parts


def _abstract(rng: random.Random) -> list[str]:
    """Bold overlapping shapes in two complementary hues over a soft gradient."""
    hue = rng.uniform(0, 360)
    parts = _gradient_sky(
        rng, palette.hsl(hue, 0.5, 0.94), palette.hsl(hue + 40, 0.5, 0.85), "ground"
    )
    for _ in range(rng.randint(9, 14)):
        colour = palette.hsl(hue + rng.choice((0, 25, 180, 205)), 0.7, rng.uniform(0.45, 0.72))
        x, y, s = rng.uniform(0, WIDTH), rng.uniform(0, HEIGHT), rng.uniform(50, 170)
        shape = rng.choice(("circle", "circle", "square", "triangle", "arc", "stripes"))
        if shape == "circle":
            parts.append(el("circle", cx=x, cy=y, r=s / 2, fill=colour, opacity=0.8))
        elif shape == "square":
            parts.append(el("rect", x=x, y=y, width=s, height=s, rx=s / 8, fill=colour, opacity=0.8,
                            transform=f"rotate({rng.uniform(0, 90):.0f} {x:.0f} {y:.0f})"))  # fmt: skip
        elif shape == "triangle":
            parts.append(path("M", x, y - s / 2, "L", x + s / 2, y + s / 2, "L", x - s / 2, y + s / 2,
                              "Z", fill=colour, opacity=0.8))  # fmt: skip
        elif shape == "arc":
            parts.append(path("M", x - s / 2, y, "A", s / 2, s / 2, 0, 0, 1, x + s / 2, y, fill="none",
                              stroke=colour, stroke_width=s / 5, stroke_linecap="round"))  # fmt: skip
        else:
            parts += [
                path("M", x + i * 14, y, "l", s * 0.6, -s * 0.6, stroke=colour, stroke_width=5,
                     stroke_linecap="round")
                for i in range(5)
            ]  # fmt: skip
    return parts


SCENES: dict[str, Scene] = {
    "landscape": _landscape,
    "city": _city,
    "food": _food,
    "office": _office,
    "whiteboard": _whiteboard,
    "chart": _chart,
    "screenshot": _screenshot,
    "pet": _pet,
    "product": _product,
    "people": _people,
    "abstract": _abstract,
}
SUBJECTS = tuple(SCENES)
