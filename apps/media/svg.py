"""Writing SVG text: one element at a time, every attribute value and text escaped.

The generators build their pictures from these calls, never by pasting strings, so a seed or a
label can never break out of an attribute or inject markup.
"""

from __future__ import annotations

from xml.sax.saxutils import escape, quoteattr

Number = int | float


def _value(value: object) -> str:
    if isinstance(value, float):
        text = f"{value:.1f}"
        return text[:-2] if text.endswith(".0") else text
    return str(value)


def _attributes(attrs: dict[str, object]) -> str:
    # Python names → SVG names: stroke_width → stroke-width, class_ → class.
    return "".join(
        f" {name.rstrip('_').replace('_', '-')}={quoteattr(_value(value))}"
        for name, value in attrs.items()
        if value is not None
    )


def el(tag: str, *children: str, **attrs: object) -> str:
    """One element: `el("circle", cx=4, cy=4, r=2, fill="#fff")`; children are SVG text."""
    if children:
        return f"<{tag}{_attributes(attrs)}>{''.join(children)}</{tag}>"
    return f"<{tag}{_attributes(attrs)}/>"


def text(content: str, **attrs: object) -> str:
    """A <text> element whose content is escaped."""
    return f"<text{_attributes(attrs)}>{escape(content)}</text>"


def path(*commands: object, **attrs: object) -> str:
    """A <path> from its commands: `path("M", 0, 0, "L", 4, 4, fill="none")`."""
    return el("path", d=" ".join(_value(c) for c in commands), **attrs)


def linear_gradient(gradient_id: str, stops: list[tuple[float, str]], vertical: bool = True) -> str:
    end = {"x2": 0, "y2": 1} if vertical else {"x2": 1, "y2": 0}
    return el(
        "linearGradient",
        *(el("stop", offset=offset, stop_color=colour) for offset, colour in stops),
        id=gradient_id,
        x1=0,
        y1=0,
        **end,
    )


def document(width: int, height: int, title: str, *body: str, fit: str = "meet") -> bytes:
    """A standalone SVG file of `width`×`height` user units. `fit="slice"` makes the picture
    cover whatever box an <img> gives it (banners and pictures are shown at many ratios)."""
    head = el(
        "svg",
        el("title", escape(title)),
        *body,
        xmlns="http://www.w3.org/2000/svg",
        width=width,
        height=height,
        viewBox=f"0 0 {width} {height}",
        preserveAspectRatio=f"xMidYMid {fit}",
        role="img",
    )
    return head.encode()
