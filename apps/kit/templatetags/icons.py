"""Icons as inline SVG, drawn once per page: `{% icon "paperclip" size=14 %}` and, once at the end
of the shell, `{% icon_sprite page %}`.

Emoji and font glyphs render as empty boxes in a browser without those fonts (Debian's Chromium),
so an agent judging a screenshot would not see them; SVG always draws. Each use is a small
`<svg><use href="#icon-…">` pointing into one hidden sprite of `<symbol>`s, so a list of two
hundred rows does not repeat the same paths two hundred times. The drawings come from the lucide
package (a maintained icon set), plus the few marks it lacks (`OWN_DRAWINGS`); stroke, fill and
size are CSS (static/site/shell.css `svg.lucide`).

Which icons a page may use is known when its templates are compiled: the tag records each name
under the template's folder (`micromail/_row.html` → `micromail`), and the sprite holds the
icons recorded for the page's environment and for the shared shell (`site`).
"""

from __future__ import annotations

import functools
import re
from collections import defaultdict
from xml.etree import ElementTree

from django import template
from django.utils.html import format_html
from django.utils.safestring import SafeString, mark_safe
from lucide.templatetags.lucide import lucide as lucide_svg

register = template.Library()

_used: dict[str, set[str]] = defaultdict(set)  # template folder → icon names
NAME = re.compile(r"[a-z0-9]+(?:-[a-z0-9]+)*")


class IconNode(template.Node):
    def __init__(self, name: str, size: int, classes: str, label: str | None) -> None:
        self.html = format_html(
            '<svg class="lucide{}" width="{}" height="{}" {}><use href="#icon-{}"></use></svg>',
            f" {classes}" if classes else "",
            size,
            size,
            mark_safe(f'role="img" aria-label="{label}"' if label else 'aria-hidden="true"'),
            name,
        )

    def render(self, context: template.Context) -> SafeString:
        return self.html


@register.tag
def icon(parser, token) -> IconNode:
    """`{% icon "name" [size=16] [class="filled"] [label="Pinned"] %}` (literal values only: the
    icon is drawn once per page). Without a label the icon is decoration (aria-hidden)."""
    bits = token.split_contents()
    if len(bits) < 2 or not (bits[1][0] == bits[1][-1] == '"'):
        raise template.TemplateSyntaxError('{% icon %} needs a quoted icon name: {% icon "flag" %}')
    name = bits[1][1:-1]
    options = {"size": "16", "class": "", "label": ""}  # no label: decoration
    for bit in bits[2:]:
        key, _, value = bit.partition("=")
        if key not in options or not value:
            raise template.TemplateSyntaxError(
                f'{{% icon %}} option {bit!r}: allowed size=<n>, class="…", label="…"'
            )
        options[key] = value.strip('"')
    if not NAME.fullmatch(name) or _drawing(name) is None:
        raise template.TemplateSyntaxError(f"{{% icon %}}: lucide has no icon named {name!r}")
    if not options["size"].isdigit():
        raise template.TemplateSyntaxError("{% icon %} size must be a number of pixels")
    folder = (parser.origin.template_name or "site").split("/")[0] if parser.origin else "site"
    _used[folder].add(name)
    return IconNode(name, int(options["size"]), options["class"], options["label"] or None)


# Marks a real product draws that lucide has no icon for, drawn on lucide's grid and stroke
# (24 units, round caps): Outlook flags a high-importance message with a bare red "!".
OWN_DRAWINGS = {"exclamation-mark": '<path d="M12 4v10" /><path d="M12 19.5h.01" />'}


@functools.cache
def _drawing(name: str) -> str | None:
    """The icon's shapes as SVG markup (without the outer <svg>), or None if neither lucide nor
    OWN_DRAWINGS has one."""
    if name in OWN_DRAWINGS:
        return OWN_DRAWINGS[name]
    try:
        svg = ElementTree.fromstring(str(lucide_svg(name)))
    except Exception:  # lucide's IconDoesNotExist
        return None
    return "".join(ElementTree.tostring(child, encoding="unicode") for child in svg)


@functools.lru_cache(maxsize=64)
def _sprite(names: frozenset[str]) -> SafeString:
    symbols = "".join(
        f'<symbol id="icon-{name}" viewBox="0 0 24 24">{_drawing(name)}</symbol>'
        for name in sorted(names)
    )
    return mark_safe(f'<svg class="icon-sprite" aria-hidden="true" hidden>{symbols}</svg>')


@register.simple_tag
def icon_sprite(environment: str = "") -> SafeString:
    """The hidden sprite with every icon the shell and `environment`'s templates use."""
    return _sprite(frozenset(_used["site"] | _used[environment]))
