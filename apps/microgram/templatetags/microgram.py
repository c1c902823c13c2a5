"""Template tags for MicroGram pages: repeated rows and captions.

`{% row "microgram/_post.html" card=card at=card.post.posted_at %}` renders a row through
`render_fragment` (once per distinct input): the row gets exactly the named inputs, the
environment root, the page's CSRF token (a placeholder the screen cache fills per response) and,
when `at` is given, its age as compact text ("5m", "2h") — the page learns when that text next
changes, so a live page is pushed again then.
"""

from __future__ import annotations

from django import template
from django.utils.safestring import SafeString

from apps.agent_site import simclock
from apps.agent_site.fragments import render_fragment
from apps.microgram.screens import caption_parts

register = template.Library()


@register.simple_tag(takes_context=True)
def row(
    context: template.Context, template_name: str, at: float | None = None, **inputs
) -> SafeString:
    page = context["page"]
    extra = {"root": context["root"], "csrf_token": str(context.get("csrf_token", ""))}
    if at is not None:
        page.changes_at(simclock.units_changes_at(at, page.now))
        extra["ago"] = simclock.compact_ago(at, page.now)
    return render_fragment(template_name, **inputs, **extra)


@register.filter
def hashtagged(caption: str) -> list[tuple[str, bool]]:
    """`{% for text, is_tag in post.caption|hashtagged %}`: hashtags apart from the text."""
    return caption_parts(caption)


@register.filter
def compact_count(n: int) -> str:
    """Follower counts as the product writes them: 847, 12.4K, 1.2M."""
    if n >= 1_000_000:
        return f"{n / 1_000_000:.1f}".rstrip("0").rstrip(".") + "M"
    if n >= 10_000:
        return f"{n / 1000:.1f}".rstrip("0").rstrip(".") + "K"
    return f"{n:,}"


@register.filter
def thousands(n: int) -> str:
    """Like counts with separators: 3,421."""
    return f"{n:,}"
