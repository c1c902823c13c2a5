"""Template tags for MicroGram pages: captions and counts (repeated rows come from the kit:
`{% load rows %}`)."""

from __future__ import annotations

import re

from django import template

register = template.Library()
HASHTAG = re.compile(r"(#\w+)")


@register.filter
def hashtagged(caption: str) -> list[tuple[str, bool]]:
    """`{% for text, is_tag in post.caption|hashtagged %}`: the caption as (text, is_hashtag)
    pieces, so hashtags can be drawn as links."""
    return [(part, part.startswith("#")) for part in HASHTAG.split(caption) if part]


@register.filter
def compact_count(n: int) -> str:
    """Follower counts as the product writes them: 847, 12.4K, 1.2M."""
    if n >= 1_000_000:
        return f"{n / 1_000_000:.1f}".rstrip("0").rstrip(".") + "M"
    if n >= 10_000:
        return f"{n / 1000:.1f}".rstrip("0").rstrip(".") + "K"
    return f"{n:,}"
