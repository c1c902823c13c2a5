"""`{% live %}`: a live region of a page, re-rendered by the server and pushed to open pages.

    {% load live %}
    {% live "nav" id="folders" class="folders" aria-label="Folders" %}…{% endlive %}

renders `<nav id="folders" data-live class="folders" aria-label="Folders">…</nav>`. The first
argument is the element name; then `name=value` attributes whose values are filter expressions
(`datetime=page|sim_now|date:"c"`); a value of None or False leaves the attribute out, True
writes it bare. `id` is required: a pushed region finds its old self by id.

On a live re-render (`request.sentinel_live`, made by apps.kit.live for a websocket push or a
poll) the tag also records `(id, outer HTML with hx-swap-oob="true")` in
`request.sentinel_live_regions`, in page order; a region inside another region is sent as part
of the outer one only. So the push is exactly the regions the templates declare, with nothing
cut out of the HTML afterwards. A region must not sit in a fragment cached across requests
(apps.kit.fragments): a cached render would not record it.
"""

from __future__ import annotations

import re

from django import template
from django.template.base import FilterExpression, NodeList, Parser, Token
from django.utils.html import conditional_escape
from django.utils.safestring import SafeString, mark_safe

from apps.kit import request_attrs

register = template.Library()

ELEMENT = re.compile(r"[a-zA-Z][a-zA-Z0-9-]*")
ATTRIBUTE = re.compile(r"[a-zA-Z_:][-a-zA-Z0-9_:.]*")
VOID_ELEMENTS = {
    "area",
    "base",
    "br",
    "col",
    "embed",
    "hr",
    "img",
    "input",
    "link",
    "meta",
    "source",
    "track",
    "wbr",
}
RESERVED = {"data-live", "hx-swap-oob"}  # written by the tag itself
USAGE = '{% live "nav" id="folders" class="…" %}…{% endlive %}'


@register.tag("live")
def live_region(parser: Parser, token: Token) -> LiveRegionNode:
    bits = token.split_contents()
    if len(bits) < 2 or ("=" in bits[1] and ATTRIBUTE.fullmatch(bits[1].partition("=")[0])):
        raise template.TemplateSyntaxError(
            f"{{% live %}} takes the element name first, then name=value attributes: {USAGE}"
        )
    element = parser.compile_filter(bits[1])
    attributes: list[tuple[str, FilterExpression]] = []
    for bit in bits[2:]:
        name, equals, value = bit.partition("=")
        if not equals or not value or not ATTRIBUTE.fullmatch(name):
            raise template.TemplateSyntaxError(
                f"{{% live %}} attribute {bit!r} is not name=value: {USAGE}"
            )
        if name in RESERVED or any(name == seen for seen, _ in attributes):
            raise template.TemplateSyntaxError(
                f"{{% live %}} attribute {name!r} is given twice or written by the tag itself"
            )
        attributes.append((name, parser.compile_filter(value)))
    if not any(name == "id" for name, _ in attributes):
        raise template.TemplateSyntaxError(
            f"{{% live {bits[1]} %}} needs an id=…: a pushed region replaces the element with "
            f"the same id, e.g. {USAGE}"
        )
    nodelist = parser.parse(("endlive",))
    parser.delete_first_token()
    return LiveRegionNode(element, attributes, nodelist)


class LiveRegionNode(template.Node):
    def __init__(
        self,
        element: FilterExpression,
        attributes: list[tuple[str, FilterExpression]],
        nodelist: NodeList,
    ) -> None:
        self.element, self.attributes, self.nodelist = element, attributes, nodelist

    def render(self, context: template.Context) -> SafeString:
        element = str(self.element.resolve(context))
        if not ELEMENT.fullmatch(element) or element.lower() in VOID_ELEMENTS:
            raise template.TemplateSyntaxError(
                f"{{% live %}} element {element!r} must be an element name with an end tag"
            )
        values = {name: value.resolve(context) for name, value in self.attributes}
        region_id = values["id"]
        if region_id is None or isinstance(region_id, bool) or str(region_id) == "":
            raise template.TemplateSyntaxError(f"{{% live {element} %}} id is empty")
        request = getattr(context, "request", None) or context.get("request")
        recording = request_attrs.is_live(request)
        if recording:  # only the outermost region is sent (it holds the inner ones)
            with request_attrs.live_region(request) as outermost:
                inner = self.nodelist.render(context)
        else:
            inner = self.nodelist.render(context)
        end = f"</{element}>"
        if recording and outermost:
            request_attrs.live_regions(request).append(
                (str(region_id), f"{start_tag(element, values, oob=True)}{inner}{end}")
            )
        # One copy of what may be most of the page (a region holds the whole message list).
        return mark_safe(f"{start_tag(element, values)}{inner}{end}")


def start_tag(element: str, values: dict, *, oob: bool = False) -> str:
    """`<element id=… data-live [hx-swap-oob="true"] …>`, attribute values escaped."""
    parts = [element, f'id="{conditional_escape(values["id"])}"', "data-live"]
    if oob:
        parts.append('hx-swap-oob="true"')
    for name, value in values.items():
        if name == "id" or value is None or value is False:
            continue
        parts.append(name if value is True else f'{name}="{conditional_escape(value)}"')
    return f"<{' '.join(parts)}>"
