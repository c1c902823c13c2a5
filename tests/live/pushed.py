"""Reading a push in tests: the regions of a `regions` message, by id."""

from __future__ import annotations

import re

# The tag writes a pushed region's start tag as `<name id="…" data-live hx-swap-oob="true"`;
# regions inside a region are sent as part of it, without the swap attribute.
_REGION_START = re.compile(r'<[a-zA-Z][\w-]* id="([^"]+)" data-live hx-swap-oob="true"')


def regions(message: dict) -> dict[str, str]:
    """{id: outer HTML} of the regions a push carries."""
    html = message["html"]
    starts = list(_REGION_START.finditer(html))
    ends = [match.start() for match in starts[1:]] + [len(html)]
    return {
        match.group(1): html[match.start() : end].strip()
        for match, end in zip(starts, ends, strict=True)
    }
