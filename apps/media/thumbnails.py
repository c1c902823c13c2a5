"""Video thumbnails: a picture's scene with a few of the title's words in large bold type, the
way real thumbnails carry them.

Two shapes. *Wide* (16:9, 480×270) cuts the middle of the 480×320 picture, as posters do, and
sets the caption over it. *Tall* (9:16, 270×480, for shorts) is composed for portrait: the scene
blown up and blurred fills the frame, the subject sits sharp in a square in the middle, the caption
stacks large above it — a vertical video's look, not a landscape picture cut narrow.

The scene comes from the seed's draws (so it matches the picture and poster of the same seed);
the caption is its own slug (`"skyward-colony-2"` → SKYWARD COLONY 2) and only its layout draws
from the caption's randomness. Both are in the URL, which is all it takes to draw it again.
"""

from __future__ import annotations

import functools
import random
import re

from apps.media import images
from apps.media.links import UNNAMED, seeded_random
from apps.media.pictures import HEIGHT as PICTURE_HEIGHT
from apps.media.pictures import SCENES, check_subject
from apps.media.pictures import WIDTH as PICTURE_WIDTH
from apps.media.svg import document, el, linear_gradient, text

WIDE = (480, 270)
TALL = (270, 480)
CAPTION_WORDS = 3
THUMBNAILS_KEPT = 1024
FONT = "'Arial Black', 'Helvetica Neue', Impact, Arial, sans-serif"
ACCENTS = ("#ffe14d", "#7df9ff", "#ff6b5c")  # the colour of the highlighted line


def _words(text: str) -> frozenset[str]:
    return frozenset(text.split())


# Words a thumbnail never spends space on.
SMALL_WORDS = _words(
    "a an and are as at be but by for from how i in into is it its my of on or our so than that "
    "the their this to up vs was we what when who why will with you your"
)
# Words a caption does not end on (they promise a word that was cut off).
DANGLING = _words(
    "about after before been can do does get go had has have one over own under use without won"
)
_WORD = re.compile(r"[A-Za-z0-9$%]+(?:'[A-Za-z]+)?")


def headline(title: str) -> str:
    """The 1–3 words of `title` a thumbnail shows: its first clause (before a colon, dash or
    question mark) without the small words, at most three and not ending on a word that promises
    more: "V4 Project at Mission Cliffs: Six…" → "V4 Project Mission". A possessive loses its "'s" (the slug has no apostrophe)."""
    clauses = [c for c in re.split(r"[:?!|]| - | — |, ", title) if c.strip()]
    words: list[str] = []
    for clause in clauses:
        words += [
            w.split("'")[0]
            for w in _WORD.findall(clause)
            if w.lower() not in SMALL_WORDS and w.split("'")[0]
        ]
        if len(words) >= 2:
            break
    words = words[:CAPTION_WORDS]
    while len(words) > 1 and words[-1].lower() in DANGLING:
        words.pop()
    return " ".join(words)


def caption_lines(caption_slug: str, longest: int) -> list[str]:
    """The caption's words, upper case, in lines of at most `longest` characters (a word longer
    than that has a line to itself)."""
    if caption_slug == UNNAMED:
        return []
    lines: list[str] = []
    for word in caption_slug.upper().split("-"):
        if lines and len(lines[-1]) + 1 + len(word) <= longest:
            lines[-1] += " " + word
        else:
            lines.append(word)
    return lines


def _font_size(lines: list[str], width: float, largest: float) -> float:
    """As large as fits `width` (heavy capitals run up to about 0.8 em wide)."""
    return min(largest, width / (0.8 * max(len(line) for line in lines)))


def _caption(
    lines: list[str], rng: random.Random, x: float, y: float, size: float, anchor: str
) -> str:
    """The lines in heavy type, white with a dark outline and shadow; one line in an accent."""
    accent = rng.randrange(len(lines)) if len(lines) > 1 else -1
    ink = rng.choice(ACCENTS)
    tilt = rng.choice((0, 0, -2, -3))
    rows = []
    for i, line in enumerate(lines):
        baseline = y + size * (i + 1) * 0.98
        common = {
            "x": x,
            "y": baseline,
            "font_family": FONT,
            "font_size": size,
            "font_weight": 900,
            "text_anchor": anchor,
        }
        rows.append(text(line, fill="#000000", opacity=0.55, transform="translate(3 4)", **common))
        rows.append(
            text(
                line,
                fill=ink if i == accent else "#ffffff",
                stroke="#111111",
                stroke_width=max(3.0, size / 9),
                stroke_linejoin="round",
                paint_order="stroke",
                **common,
            )
        )
    return el("g", *rows, transform=f"rotate({tilt} {x:.0f} {y:.0f})", class_="caption")


def wide(seed_slug: str, subject: str, caption_slug: str) -> bytes:
    """The 16:9 thumbnail: the scene's middle band, a shade where the words sit, the words."""
    width, height = WIDE
    scene = SCENES[check_subject(subject)](seeded_random(seed_slug))
    rng = seeded_random(caption_slug)
    lines = caption_lines(caption_slug, 12)
    body = [el("g", *scene, transform=f"translate(0 {-(PICTURE_HEIGHT - height) / 2:.0f})")]
    if lines:
        at_top = rng.random() < 0.5
        # Along the bottom, the words keep clear of the corner where a player sets the duration.
        size = _font_size(lines, width * (0.9 if at_top else 0.68), 64 if len(lines) < 3 else 50)
        block = size * len(lines)
        top = 14 if at_top else height - block - 26
        shade = [(0, "rgba(0,0,0,0.55)"), (1, "rgba(0,0,0,0)")]
        if not at_top:
            shade = [(0, "rgba(0,0,0,0)"), (1, "rgba(0,0,0,0.6)")]
        shade_top = 0 if at_top else top - 30
        body += [
            el("defs", linear_gradient("caption-shade", shade)),
            el("rect", y=shade_top, width=width, height=block + 50, fill="url(#caption-shade)"),
            _caption(lines, rng, 18, top, size, "start"),
        ]
    return document(width, height, f"{subject} {seed_slug}: {caption_slug}", *body, fit="slice")


def portrait(scene: list[str], subject_top: float) -> list[str]:
    """A 3:2 scene composed for a 9:16 frame (TALL): the scene blown up and blurred behind, a
    square from its middle sharp at `subject_top`, fading into it, a shade along the foot."""
    width, height = TALL
    cover = height / PICTURE_HEIGHT  # the backdrop covers the frame's height
    side = PICTURE_HEIGHT  # a square from the middle of the scene
    square = width / side
    left = (PICTURE_WIDTH - side) / 2
    return [
        el(
            "defs",
            el(
                "filter",
                el("feGaussianBlur", stdDeviation=9),
                id="backdrop-blur",
                x="-5%",
                y="-5%",
                width="110%",
                height="110%",
            ),
            # The subject's square fades into the backdrop at its top and bottom (no hard edge).
            el(
                "mask",
                el("rect", x=left, y=0, width=side, height=side, fill="url(#square-fade)"),
                id="subject-square",
            ),
            linear_gradient(
                "square-fade",
                [(0, "#000000"), (0.14, "#ffffff"), (0.86, "#ffffff"), (1, "#000000")],
            ),
            linear_gradient("foot", [(0, "rgba(0,0,0,0)"), (1, "rgba(0,0,0,0.55)")]),
        ),
        el(
            "g",
            el("g", *scene, filter="url(#backdrop-blur)"),
            transform=f"translate({(width - PICTURE_WIDTH * cover) / 2:.1f} 0) scale({cover:.3f})",
        ),
        el("rect", width=width, height=height, fill="#000000", opacity=0.28),
        el(
            "g",
            el("g", *scene, mask="url(#subject-square)"),
            transform=f"translate({-left * square:.1f} {subject_top:.1f}) scale({square:.4f})",
        ),
        el("rect", y=height * 0.72, width=width, height=height * 0.28, fill="url(#foot)"),
    ]


def tall(seed_slug: str, subject: str, caption_slug: str) -> bytes:
    """The 9:16 thumbnail of a short: blurred scene behind, the subject sharp in the middle,
    the caption stacked large above it."""
    width, height = TALL
    scene = SCENES[check_subject(subject)](seeded_random(seed_slug))
    rng = seeded_random(caption_slug)
    lines = caption_lines(caption_slug, 9)[:4]
    subject_top = height * 0.36
    body = portrait(scene, subject_top)
    if lines:
        size = _font_size(lines, width * 0.9, 46)
        top = max(10.0, subject_top - size * len(lines) - 8)
        body.append(_caption(lines, rng, width / 2, top, size, "middle"))
    return document(width, height, f"{subject} {seed_slug}: {caption_slug}", *body, fit="slice")


SHAPES = {"wide": wide, "tall": tall}


@functools.lru_cache(maxsize=THUMBNAILS_KEPT)
def drawn_thumbnail(shape: str, subject: str, seed_slug: str, caption_slug: str) -> images.Image:
    """The thumbnail (`shape` one of SHAPES) with its ETag."""
    return images.tagged(SHAPES[shape](seed_slug, subject, caption_slug))
