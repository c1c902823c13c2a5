"""Colours shared by the generators, and small colour arithmetic.

Skin tones span a realistic range (light to deep), hair colours are mostly natural with a few
dyed ones, backgrounds are soft so a face stands out, brand pairs are saturated so a logo does.
"""

from __future__ import annotations

import colorsys
import random

SKIN_TONES = (
    "#ffdfc4", "#f6d2b4", "#f0c8a0", "#eab98f", "#e0ac7e", "#d39a6a",
    "#c68652", "#b06f42", "#9a5b35", "#86492a", "#6f3a22", "#5a2e1b",
)  # fmt: skip
HAIR_COLOURS = (
    "#1f1a17", "#2b211c", "#3b2a20", "#4e3525", "#6a4630", "#8a5a36",
    "#a8733f", "#c9994f", "#dcbc7c", "#b8472a", "#8e3a22", "#9a9a9a", "#d4d4d4",
)  # fmt: skip
DYED_HAIR = ("#5b4b8a", "#2f6f8f", "#b04a7a")
BACKGROUNDS = (
    "#dbeafe", "#e0e7ff", "#ede9fe", "#fae8ff", "#fce7f3", "#ffe4e6", "#ffedd5",
    "#fef3c7", "#ecfccb", "#dcfce7", "#d1fae5", "#ccfbf1", "#cffafe", "#e0f2fe",
)  # fmt: skip
CLOTHES = (
    "#1e3a8a", "#1d4ed8", "#0f766e", "#15803d", "#4d7c0f", "#a16207", "#c2410c",
    "#b91c1c", "#be185d", "#7e22ce", "#4338ca", "#334155", "#1f2937", "#f8fafc",
    "#e2e8f0", "#f59e0b", "#0ea5e9", "#64748b",
)  # fmt: skip
# (background, foreground) pairs that read like brand colours.
BRAND_PAIRS = (
    ("#0f62fe", "#ffffff"), ("#111827", "#f59e0b"), ("#16a34a", "#ffffff"),
    ("#dc2626", "#ffffff"), ("#7c3aed", "#ffffff"), ("#0891b2", "#ffffff"),
    ("#f97316", "#ffffff"), ("#db2777", "#ffffff"), ("#0f172a", "#38bdf8"),
    ("#fde047", "#1f2937"), ("#ffffff", "#2563eb"), ("#ffffff", "#e11d48"),
    ("#ecfdf5", "#047857"), ("#1e1b4b", "#a5b4fc"), ("#14532d", "#bef264"),
    ("#fff7ed", "#c2410c"), ("#0c4a6e", "#7dd3fc"), ("#312e81", "#fbbf24"),
)  # fmt: skip


def _rgb(colour: str) -> tuple[float, float, float]:
    colour = colour.lstrip("#")
    return tuple(int(colour[i : i + 2], 16) / 255 for i in (0, 2, 4))  # type: ignore[return-value]


def _hex(r: float, g: float, b: float) -> str:
    return "#" + "".join(f"{round(max(0.0, min(1.0, c)) * 255):02x}" for c in (r, g, b))


def mix(colour: str, other: str, amount: float) -> str:
    """`colour` moved `amount` (0–1) of the way towards `other`."""
    a, b = _rgb(colour), _rgb(other)
    return _hex(*(x + (y - x) * amount for x, y in zip(a, b, strict=True)))


def shade(colour: str, amount: float) -> str:
    """Darker (amount > 0) or lighter (amount < 0) by mixing with black or white."""
    return mix(colour, "#000000", amount) if amount >= 0 else mix(colour, "#ffffff", -amount)


def hsl(hue: float, saturation: float, lightness: float) -> str:
    """A colour from hue in degrees and saturation/lightness in 0–1."""
    return _hex(*colorsys.hls_to_rgb((hue % 360) / 360, lightness, saturation))


def lightness(colour: str) -> float:
    r, g, b = _rgb(colour)
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


def ramp(rng: random.Random, steps: int, saturation: float = 0.45) -> list[str]:
    """`steps` colours of one hue from light to dark (layers of a landscape, bars of a chart)."""
    hue = rng.uniform(0, 360)
    return [
        hsl(hue + i * rng.uniform(-8, 8), saturation, 0.82 - 0.55 * i / max(1, steps - 1))
        for i in range(steps)
    ]
