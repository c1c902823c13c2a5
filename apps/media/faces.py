"""Avatars: an illustrated head-and-shoulders portrait drawn from a slug.

Flat-illustration style (the look of many products' default avatars): a soft background, the
shoulders in a shirt, a face with a skin tone from a realistic range, one of a dozen hair styles
in a natural (now and then dyed) colour, eyes, brows, nose, mouth, sometimes glasses, a beard or
earrings. Shapes are large and few so the person still reads at 24 px.
"""

from __future__ import annotations

import random
from dataclasses import dataclass

from apps.media import palette
from apps.media.svg import document, el, path

SIZE = 128
CX = 64  # the face's vertical axis
CLOSE_UP, CLOSE_UP_ANCHOR = 1.16, 116  # avatar framing: scale about a point below the chin
HAIR_STYLES = (
    "crop", "side", "quiff", "buzz", "bald", "curly", "afro",
    "long", "bob", "bun", "wavy", "scarf",
)  # fmt: skip
LONG_STYLES = {"long", "bob", "wavy"}


@dataclass(frozen=True)
class Head:
    """Where the face sits: its top, the eye line, its half-width and the chin."""

    top: float
    eyes: float
    half_width: float
    chin: float

    @property
    def left(self) -> float:
        return CX - self.half_width

    @property
    def right(self) -> float:
        return CX + self.half_width


def portrait(rng: random.Random, slug: str) -> bytes:
    """The avatar of `slug`: a 128×128 SVG (square; the page decides round or rounded)."""
    background = rng.choice(palette.BACKGROUNDS)
    # Framed close (the head fills about half the width) so a 24 px avatar still shows a face.
    return document(
        SIZE, SIZE, f"Avatar {slug}", el("rect", width=SIZE, height=SIZE, fill=background),
        el("g", *_person(rng), transform=f"translate({CX} {CLOSE_UP_ANCHOR}) scale({CLOSE_UP})"
           f" translate({-CX} {-CLOSE_UP_ANCHOR})"),
        fit="slice",
    )  # fmt: skip


def portrait_figure(rng: random.Random, x: float, bottom: float, scale: float) -> str:
    """A person (head and shoulders, no background) centred on `x`, standing on `bottom`: the
    figures of group pictures."""
    return el(
        "g", *_person(rng),
        transform=f"translate({x - CX * scale:.1f} {bottom - SIZE * scale:.1f}) scale({scale:.2f})",
    )  # fmt: skip


def _person(rng: random.Random) -> list[str]:
    head = Head(
        top=rng.uniform(28, 32),
        eyes=rng.uniform(58, 61),
        half_width=rng.uniform(22.5, 26),
        chin=rng.uniform(86, 90),
    )
    skin = rng.choice(palette.SKIN_TONES)
    style = rng.choice(HAIR_STYLES)
    natural = palette.HAIR_COLOURS if style in {"bald", "buzz"} else palette.HAIR_COLOURS[:-2]
    hair = rng.choice(palette.DYED_HAIR) if rng.random() < 0.06 else rng.choice(natural)
    if abs(palette.lightness(hair) - palette.lightness(skin)) < 0.15:
        # Hair the colour of the skin reads as a bald head at 24 px: take the darkest instead.
        hair = palette.HAIR_COLOURS[0]
    scarf = rng.choice(palette.CLOTHES[:13])
    shirt = rng.choice(palette.CLOTHES)
    bearded = style in {"crop", "side", "quiff", "buzz", "bald", "curly"} and rng.random() < 0.35
    glasses = rng.random() < 0.28
    earrings = style in LONG_STYLES | {"bun", "afro"} and rng.random() < 0.4

    parts = [_scarf_back(head, scarf) if style == "scarf" else _hair_back(style, head, hair)]
    parts += _shoulders(rng, head, skin, shirt)
    if style != "scarf":
        parts.append(_ears(head, skin))
    parts.append(_face(head, skin))
    if bearded:
        parts.append(_beard(rng, head, hair))
    parts += _features(rng, head, skin, hair)
    if style == "scarf":
        parts.append(_scarf_front(head, scarf))
    else:
        parts.append(_hair_front(rng, style, head, hair))
    if glasses:
        parts.append(_glasses(rng, head))
    if earrings:
        parts.append(_earrings(head, rng.choice(("#f5c542", "#e5e7eb", "#f472b6"))))
    return [part for part in parts if part]


def _shoulders(rng: random.Random, head: Head, skin: str, shirt: str) -> list[str]:
    neck_top, shoulder = head.chin - 14, 102
    collar = rng.choice(("crew", "vee", "shirt", "turtle", "hoodie"))
    parts = [
        el("rect", x=CX - 10, y=neck_top, width=20, height=shoulder - neck_top + 6, rx=6,
           fill=palette.shade(skin, 0.14)),
        path("M", 10, SIZE, "C", 10, 110, 30, shoulder - 2, 50, shoulder - 4, "L", 78, shoulder - 4,
             "C", 98, shoulder - 2, 118, 110, 118, SIZE, "Z", fill=shirt),
    ]  # fmt: skip
    edge = (
        palette.shade(shirt, 0.18)
        if palette.lightness(shirt) > 0.25
        else palette.shade(shirt, -0.25)
    )
    if collar == "crew":
        parts.append(path("M", 50, shoulder - 4, "Q", CX, shoulder + 10, 78, shoulder - 4,
                          fill=palette.shade(skin, 0.14), stroke=edge, stroke_width=2.5))  # fmt: skip
    elif collar == "vee":
        parts.append(path("M", 50, shoulder - 4, "L", CX, shoulder + 16, "L", 78, shoulder - 4, "Z",
                          fill=palette.shade(skin, 0.14), stroke=edge, stroke_width=2.5,
                          stroke_linejoin="round"))  # fmt: skip
    elif collar == "shirt":
        white = "#ffffff" if palette.lightness(shirt) < 0.8 else "#cbd5e1"
        parts += [
            path("M", 52, shoulder - 4, "L", CX, shoulder + 12, "L", 76, shoulder - 4, "Z",
                 fill=palette.shade(skin, 0.14)),
            path("M", 50, shoulder - 6, "L", CX - 1, shoulder + 12, "L", 54, shoulder + 16,
                 "L", 45, shoulder + 2, "Z", fill=white, stroke=edge, stroke_width=1),
            path("M", 78, shoulder - 6, "L", CX + 1, shoulder + 12, "L", 74, shoulder + 16,
                 "L", 83, shoulder + 2, "Z", fill=white, stroke=edge, stroke_width=1),
        ]  # fmt: skip
    elif collar == "turtle":
        parts.append(el("rect", x=CX - 12, y=shoulder - 12, width=24, height=14, rx=6,
                        fill=palette.shade(shirt, 0.1)))  # fmt: skip
    else:  # hoodie: a hood behind the neck and two strings
        parts += [
            path("M", 44, shoulder - 2, "Q", CX, shoulder + 16, 84, shoulder - 2,
                 fill="none", stroke=palette.shade(shirt, 0.2), stroke_width=6,
                 stroke_linecap="round"),
            path("M", CX - 6, shoulder + 6, "L", CX - 7, shoulder + 18, "M", CX + 6,
                 shoulder + 6, "L", CX + 7, shoulder + 18, stroke="#f8fafc", stroke_width=1.6,
                 stroke_linecap="round"),
        ]  # fmt: skip
    return parts


def _ears(head: Head, skin: str) -> str:
    y = head.eyes + 4
    inner = palette.shade(skin, 0.12)
    return el(
        "g",
        el("ellipse", cx=head.left + 0.5, cy=y, rx=4.5, ry=7, fill=skin),
        el("ellipse", cx=head.right - 0.5, cy=y, rx=4.5, ry=7, fill=skin),
        el("ellipse", cx=head.left + 0.5, cy=y, rx=2, ry=3.8, fill=inner),
        el("ellipse", cx=head.right - 0.5, cy=y, rx=2, ry=3.8, fill=inner),
    )


def _face_outline(head: Head) -> list[object]:
    k = 0.56  # the quarter-ellipse control-point ratio
    cheek = head.eyes + 2
    return [
        "M", CX, head.top,
        "C", CX + head.half_width * k, head.top, head.right, cheek - (cheek - head.top) * k,
        head.right, cheek,
        "C", head.right, cheek + (head.chin - cheek) * 0.55, CX + head.half_width * 0.55, head.chin,
        CX, head.chin,
        "C", CX - head.half_width * 0.55, head.chin, head.left, cheek + (head.chin - cheek) * 0.55,
        head.left, cheek,
        "C", head.left, cheek - (cheek - head.top) * k, CX - head.half_width * k, head.top,
        CX, head.top, "Z",
    ]  # fmt: skip


def _face(head: Head, skin: str) -> str:
    return path(*_face_outline(head), fill=skin)


def _features(rng: random.Random, head: Head, skin: str, hair: str) -> list[str]:
    eye_y, spread = head.eyes, rng.uniform(8.5, 10)
    ink = "#2a211c"
    brow = hair if palette.lightness(hair) < 0.45 else palette.shade(hair, 0.45)
    lift = rng.uniform(-1.2, 1.2)
    blush = "#e8807a"
    parts = [
        el("circle", cx=CX - 14, cy=eye_y + 10, r=4.5, fill=blush, opacity=0.22),
        el("circle", cx=CX + 14, cy=eye_y + 10, r=4.5, fill=blush, opacity=0.22),
    ]
    if rng.random() < 0.15:  # smiling, closed eyes
        for side in (-1, 1):
            x = CX + side * spread
            parts.append(path("M", x - 3.2, eye_y + 0.8, "Q", x, eye_y - 2.6, x + 3.2, eye_y + 0.8,
                              fill="none", stroke=ink, stroke_width=2, stroke_linecap="round"))  # fmt: skip
    else:
        for side in (-1, 1):
            x = CX + side * spread
            parts += [
                el("ellipse", cx=x, cy=eye_y, rx=2.5, ry=2.9, fill=ink),
                el("circle", cx=x + 0.8, cy=eye_y - 0.9, r=0.8, fill="#ffffff"),
            ]
    for side in (-1, 1):
        x = CX + side * spread
        parts.append(path("M", x - side * 4, eye_y - 6.5 + lift, "Q", x, eye_y - 9 + lift,
                          x + side * 4.2, eye_y - 6.8, fill="none", stroke=brow, stroke_width=2.3,
                          stroke_linecap="round"))  # fmt: skip
    nose = palette.shade(skin, 0.22)
    parts.append(path("M", CX - 0.5, eye_y + 4, "Q", CX + 3.5, eye_y + 11, CX + 0.5, eye_y + 12.5,
                      "Q", CX - 1.5, eye_y + 13, CX - 3, eye_y + 12, fill="none", stroke=nose,
                      stroke_width=1.8, stroke_linecap="round"))  # fmt: skip
    mouth_y = eye_y + 19
    lips = palette.mix("#a23b3b", skin, 0.35)
    mood = rng.choice(("grin", "smile", "smile", "calm"))
    if mood == "grin":
        parts += [
            path("M", CX - 7.5, mouth_y - 1, "Q", CX, mouth_y + 1, CX + 7.5, mouth_y - 1,
                 "Q", CX, mouth_y + 10, CX - 7.5, mouth_y - 1, "Z", fill="#7a2a2a"),
            path("M", CX - 6, mouth_y - 0.2, "Q", CX, mouth_y + 1.4, CX + 6, mouth_y - 0.2,
                 "L", CX + 5, mouth_y + 2, "Q", CX, mouth_y + 3, CX - 5, mouth_y + 2, "Z",
                 fill="#ffffff"),
        ]  # fmt: skip
    elif mood == "smile":
        parts.append(path("M", CX - 6.5, mouth_y, "Q", CX, mouth_y + 5.5, CX + 6.5, mouth_y,
                          fill="none", stroke=lips, stroke_width=2.4, stroke_linecap="round"))  # fmt: skip
    else:
        parts.append(path("M", CX - 5, mouth_y + 1, "Q", CX, mouth_y + 2.5, CX + 5, mouth_y + 1,
                          fill="none", stroke=lips, stroke_width=2.4, stroke_linecap="round"))  # fmt: skip
    return parts


def _beard(rng: random.Random, head: Head, hair: str) -> str:
    kind = rng.choice(("full", "full", "stubble", "moustache", "goatee"))
    mouth_y = head.eyes + 19
    if kind == "moustache":
        return path("M", CX - 8, mouth_y - 1, "Q", CX - 4, mouth_y - 6, CX, mouth_y - 4,
                    "Q", CX + 4, mouth_y - 6, CX + 8, mouth_y - 1, "Q", CX, mouth_y - 3,
                    CX - 8, mouth_y - 1, "Z", fill=hair)  # fmt: skip
    if kind == "goatee":
        return path("M", CX - 6, mouth_y + 5, "Q", CX, mouth_y + 3, CX + 6, mouth_y + 5,
                    "Q", CX + 5, head.chin + 1, CX, head.chin + 1.5, "Q", CX - 5, head.chin + 1,
                    CX - 6, mouth_y + 5, "Z", fill=hair)  # fmt: skip
    y = head.eyes + 4
    shape = path(
        "M", head.left, y,
        "C", head.left, head.chin - 4, CX - 14, head.chin + 5, CX, head.chin + 5,
        "C", CX + 14, head.chin + 5, head.right, head.chin - 4, head.right, y,
        "L", head.right - 3, y + 2,
        "C", head.right - 5, mouth_y - 2, CX + 10, mouth_y - 8, CX, mouth_y - 6,
        "C", CX - 10, mouth_y - 8, head.left + 5, mouth_y - 2, head.left + 3, y + 2, "Z",
        fill=hair, opacity=0.3 if kind == "stubble" else 1,
    )  # fmt: skip
    return shape


def _glasses(rng: random.Random, head: Head) -> str:
    frame = rng.choice(("#1f2937", "#1f2937", "#7c2d12", "#334155", "#b45309"))
    spread, y = 9.5, head.eyes
    round_ = rng.random() < 0.5
    lenses = []
    for side in (-1, 1):
        x = CX + side * spread
        if round_:
            lenses.append(el("circle", cx=x, cy=y, r=6.5, fill="#ffffff", fill_opacity=0.18,
                             stroke=frame, stroke_width=2))  # fmt: skip
        else:
            lenses.append(el("rect", x=x - 7, y=y - 5, width=14, height=10.5, rx=3, fill="#ffffff",
                             fill_opacity=0.18, stroke=frame, stroke_width=2))  # fmt: skip
    bridge = path("M", CX - 3, y - 1, "Q", CX, y - 3, CX + 3, y - 1, fill="none", stroke=frame,
                  stroke_width=2)  # fmt: skip
    arms = path("M", CX - spread - 7, y - 1, "L", head.left - 1, y - 2, "M", CX + spread + 7, y - 1,
                "L", head.right + 1, y - 2, stroke=frame, stroke_width=2)  # fmt: skip
    return el("g", *lenses, bridge, arms)


def _earrings(head: Head, metal: str) -> str:
    y = head.eyes + 11
    return el(
        "g",
        el("circle", cx=head.left, cy=y, r=2.2, fill=metal),
        el("circle", cx=head.right, cy=y, r=2.2, fill=metal),
    )


# Hair. The back layer sits behind the head (long hair falls over the shoulders); the front layer
# covers the top of the head down to a hairline.


def _hair_back(style: str, head: Head, hair: str) -> str:
    top, left, right = head.top, head.left, head.right
    if style == "long":
        return path("M", left - 6, head.eyes, "C", left - 8, top - 8, right + 8, top - 8, right + 6,
                    head.eyes, "L", right + 9, 108, "Q", CX, 116, left - 9, 108, "Z", fill=hair)  # fmt: skip
    if style == "wavy":
        return path("M", left - 6, head.eyes, "C", left - 8, top - 8, right + 8, top - 8, right + 6,
                    head.eyes, "C", right + 14, 80, right + 2, 92, right + 12, 106,
                    "Q", CX, 114, left - 12, 106, "C", left - 2, 92, left - 14, 80, left - 6,
                    head.eyes, "Z", fill=hair)  # fmt: skip
    if style == "bob":
        return path("M", left - 6, head.eyes, "C", left - 8, top - 8, right + 8, top - 8, right + 6,
                    head.eyes, "L", right + 7, head.chin - 2, "Q", right + 2, head.chin + 2,
                    right - 6, head.chin - 2, "L", left + 6, head.chin - 2, "Q", left - 2,
                    head.chin + 2, left - 7, head.chin - 2, "Z", fill=hair)  # fmt: skip
    if style == "afro":
        return el("g", *(el("circle", cx=CX + dx, cy=head.eyes - 12 + dy, r=r, fill=hair)
                         for dx, dy, r in ((0, -6, 30), (-20, 6, 20), (20, 6, 20), (-14, -16, 18),
                                           (14, -16, 18))))  # fmt: skip
    if style == "bun":
        return el("circle", cx=CX, cy=top - 5, r=10.5, fill=hair)
    return ""


def _hair_front(rng: random.Random, style: str, head: Head, hair: str) -> str:
    top, left, right, eyes = head.top, head.left, head.right, head.eyes
    temple = eyes - 4
    if style == "bald":  # a fringe of hair over the ears
        return el(
            "g",
            path("M", left - 1, temple - 2, "Q", left - 4, eyes + 6, left + 2, eyes + 4, "Z", fill=hair),
            path("M", right + 1, temple - 2, "Q", right + 4, eyes + 6, right - 2, eyes + 4, "Z", fill=hair),
        )  # fmt: skip
    if style == "buzz":
        return path("M", left - 0.5, temple, "C", left - 1, top - 4, right + 1, top - 4, right + 0.5,
                    temple, "C", right - 2, top + 14, left + 2, top + 14, left - 0.5, temple, "Z",
                    fill=hair, opacity=0.85)  # fmt: skip
    if style == "crop":
        return path("M", left - 2, temple + 2, "C", left - 4, top - 10, right + 4, top - 10,
                    right + 2, temple + 2, "L", right - 1, temple - 3, "C", right - 4, top + 12,
                    left + 4, top + 12, left + 1, temple - 3, "Z", fill=hair)  # fmt: skip
    if style == "side":
        return path("M", left - 2, temple + 2, "C", left - 4, top - 10, right + 4, top - 10,
                    right + 2, temple + 2, "L", right - 1, temple - 4, "C", right - 6, top + 8,
                    CX - 2, top + 8, CX - 6, top + 10, "C", CX - 14, top + 16, left + 4, top + 16,
                    left + 1, temple, "Z", fill=hair)  # fmt: skip
    if style == "quiff":
        return path("M", left - 2, temple + 2, "C", left - 6, top - 8, CX - 4, top - 16, CX + 8,
                    top - 12, "C", right + 2, top - 12, right + 4, top, right + 2, temple + 2,
                    "L", right - 1, temple - 3, "C", right - 4, top + 12, left + 4, top + 12,
                    left + 1, temple - 3, "Z", fill=hair)  # fmt: skip
    if style == "curly":
        curls = [
            el("circle", cx=CX + dx, cy=top + dy, r=r, fill=hair)
            for dx, dy, r in (
                (-24, 14, 7), (-20, 4, 8), (-11, -2, 8.5), (0, -4, 9), (11, -2, 8.5),
                (20, 4, 8), (24, 14, 7), (-6, 5, 7), (7, 5, 7),
            )
        ]  # fmt: skip
        return el("g", *curls)
    if style == "afro":
        return path("M", left - 1, temple + 2, "C", left - 3, top - 6, right + 3, top - 6,
                    right + 1, temple + 2, "C", right - 4, top + 10, left + 4, top + 10,
                    left - 1, temple + 2, "Z", fill=hair)  # fmt: skip
    if style == "bun":
        return path("M", left - 1, temple + 2, "C", left - 3, top - 7, right + 3, top - 7,
                    right + 1, temple + 2, "C", right - 3, top + 8, left + 3, top + 8,
                    left - 1, temple + 2, "Z", fill=hair)  # fmt: skip
    # long, wavy, bob: a parted fringe framing the face
    part = CX + rng.choice((-8, 0, 8))
    return path("M", left - 4, eyes + 8, "C", left - 6, top - 8, right + 6, top - 8, right + 4,
                eyes + 8, "C", right - 2, temple, right - 6, top + 10, part, top + 8,
                "C", left + 6, top + 10, left + 2, temple, left - 4, eyes + 8, "Z", fill=hair)  # fmt: skip


def _scarf_back(head: Head, cloth: str) -> str:
    return path("M", head.left - 8, head.eyes, "C", head.left - 10, head.top - 12, head.right + 10,
                head.top - 12, head.right + 8, head.eyes, "L", head.right + 12, 106, "Q", CX, 116,
                head.left - 12, 106, "Z", fill=cloth)  # fmt: skip


def _scarf_front(head: Head, cloth: str) -> str:
    # The cloth framing the face: an outer band over the forehead and down both cheeks.
    inner = palette.shade(cloth, 0.15)
    return path("M", head.left - 4, head.chin, "C", head.left - 8, head.top - 8, head.right + 8,
                head.top - 8, head.right + 4, head.chin, "L", head.right - 1, head.eyes + 6,
                "C", head.right - 2, head.top + 6, head.left + 2, head.top + 6, head.left + 1,
                head.eyes + 6, "Z", fill=inner)  # fmt: skip
