"""Template tags for MicroTube pages: counts and ages on the simulated clock, repeated rows.

Everything here that moves with the clock tells the page when its text next changes
(`page.changes_at`), so a kept or live page is rendered again exactly then:

    {{ video|views:page }}            684K views (drifting with the clock)
    {{ video|likes:page }}            31K
    {% subscribers channel %}         1.42M subscribers (plus the user's own subscription)
    {{ video.published_at|yt_ago:page }}   3 days ago
    {% video_cards cards "grid" %}    each card once per distinct input (render_fragment)
    {% comment_rows comments %}
"""

from __future__ import annotations

from django import template
from django.utils.safestring import SafeString, mark_safe

from apps.kit.fragments import render_fragment
from apps.kit.streaming import shown_count
from apps.media.templatetags import media
from apps.microtube import display
from apps.microtube.state import Channel, Video

register = template.Library()


@register.filter
def views(video: Video, page) -> str:
    return display.views_text(display.moving(page, video.views))


@register.filter
def likes(video: Video, page) -> str:
    return display.compact(display.moving(page, video.likes))


@register.filter
def yt_ago(at: float, page) -> str:
    page.ages_at(display.ago_changes_at(at, page.now))
    return display.ago(at, page.now)


@register.simple_tag(takes_context=True)
def subscribers(context: template.Context, channel: Channel) -> str:
    """The shown count: the drifting catalog number, rounded for display, plus the user's own
    subscription (+1), as the original's channel page showed it."""
    page = context["page"]
    value = display.moving(page, channel.subscribers, digits=3)
    drifted = shown_count(value, display.count_step(value, digits=3))
    return display.subscribers_text(max(0, drifted + page.state.own_subscription(channel.id)))


@register.simple_tag(takes_context=True)
def video_cards(context: template.Context, cards, layout: str = "grid") -> SafeString:
    """Each card through `microtube/_card.html` in `layout` (grid | row | compact)."""
    page, root = context["page"], context["root"]
    html = [
        render_fragment("microtube/_private_card.html", card=card, layout=layout, root=root)
        # A private video's row shows no count nor age: nothing of it moves with the clock.
        if card.private
        else render_fragment(
            "microtube/_card.html",
            card=card,
            views=views(card.video, page),
            ago=yt_ago(card.video.published_at, page),
            live=card.video.is_live,
            layout=layout,
            root=root,
        )
        for card in cards
    ]
    return mark_safe("".join(html))


@register.simple_tag(takes_context=True)
def comment_rows(context: template.Context, comments) -> SafeString:
    page = context["page"]
    html = [
        render_fragment("microtube/_comment.html", comment=c, ago=yt_ago(c.posted_at, page))
        for c in comments
    ]
    return mark_safe("".join(html))


@register.filter
def initial(name: str) -> str:
    return name.strip()[:1].upper() if name else "?"


@register.simple_tag
def channel_avatar(channel: Channel, size: int = 36) -> SafeString:
    """A channel's round picture: the owner's face on the self user's channel, else its mark."""
    if channel.is_self:
        return media.avatar(channel.name, size=size, **{"class": "round"})
    return media.logo(channel.name, size=size, **{"class": "round"})
