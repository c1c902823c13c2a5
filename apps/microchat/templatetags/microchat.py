"""Template tags for MicroChat pages: the chat-list rows and the messages of the open chat,
each rendered once per distinct input (apps.kit.fragments), plus small filters.

Rows carry small POST forms (a star, reactions). A cached fragment cannot hold the request's
CSRF token, so it is rendered with a placeholder that the tag swaps for the page's token.
"""

from __future__ import annotations

from datetime import date, timedelta

from django import template
from django.utils.safestring import SafeString, mark_safe

from apps.kit import simclock
from apps.kit.fragments import render_fragment
from apps.kit.templatetags.simtime import sim_ago
from apps.microchat.markup import render_markup
from apps.microchat.screens import ConversationRow, MessageView, OpenConversation

register = template.Library()
register.filter("sim_ago", sim_ago)

CSRF_PLACEHOLDER = "__microchat_csrf__"
REACTION_ICONS = {
    "like": "thumbs-up",
    "heart": "heart",
    "laugh": "laugh",
    "celebrate": "party-popper",
    "sad": "frown",
    "angry": "angry",
}
REACTION_LABELS = {
    "like": "Like",
    "heart": "Heart",
    "laugh": "Laugh",
    "celebrate": "Celebrate",
    "sad": "Sad",
    "angry": "Angry",
}


def day_text(at: float, now: float, zero: date) -> str:
    """How Teams dates a chat's last message: today's time, "Yesterday", else d/m."""
    then, today = simclock.moment(at, zero).date(), simclock.today(now, zero)
    if then == today:
        return simclock.clock_time(at)
    if then == today - timedelta(days=1):
        return "Yesterday"
    return f"{then.day}/{then.month}"


def stamp_text(at: float, now: float, zero: date) -> str:
    """A message's header time: "09:12", "Yesterday 17:30", "Mon 3/3 10:05"."""
    then, today = simclock.moment(at, zero), simclock.today(now, zero)
    clock = simclock.clock_time(at)
    if then.date() == today:
        return clock
    if then.date() == today - timedelta(days=1):
        return f"Yesterday {clock}"
    return f"{then:%a} {then.day}/{then.month} {clock}"


def _with_token(html: str, context: template.Context) -> SafeString:
    return mark_safe(html.replace(CSRF_PLACEHOLDER, str(context.get("csrf_token", ""))))


@register.simple_tag(takes_context=True)
def conversation_rows(context: template.Context, rows: tuple[ConversationRow, ...]) -> SafeString:
    page = context["page"]
    zero = simclock.day_zero(page.run)
    back = context.get("back", "")
    html = [
        render_fragment(
            "microchat/_conversation_row.html",
            row=row,
            when=day_text(row.last_at, page.now, zero) if row.last_at is not None else "",
            root=context["root"],
            back=back,
            csrf=CSRF_PLACEHOLDER,
        )
        for row in rows
    ]
    return _with_token("".join(html), context)


@register.simple_tag(takes_context=True)
def message_items(context: template.Context, opened: OpenConversation) -> SafeString:
    page = context["page"]
    zero = simclock.day_zero(page.run)
    self_names = context["self_names"]
    html = []
    for view in opened.messages:
        html.append(
            render_fragment(
                "microchat/_message.html",
                view=view,
                body=render_markup(view.message.content, self_names),
                stamp=stamp_text(view.message.sent_at, page.now, zero),
                root=context["root"],
                back=opened.back,
                reactions=REACTION_CHOICES,
                csrf=CSRF_PLACEHOLDER,
            )
        )
    return _with_token("".join(html), context)


REACTION_CHOICES = tuple(
    (name, REACTION_ICONS[name], REACTION_LABELS[name]) for name in REACTION_ICONS
)


@register.filter
def reaction_icon(name: str) -> str:
    return REACTION_ICONS.get(name, "smile")


@register.filter
def reaction_label(name: str) -> str:
    return REACTION_LABELS.get(name, name)


@register.filter
def initials(name: str) -> str:
    return "".join(word[0] for word in name.split()[:2]).upper()


@register.simple_tag(takes_context=True)
def when_text(context: template.Context, at: float | None, fallback: str = "") -> str:
    """A call or activity time: relative to the page's clock for one that arrived during the
    run, else the catalog's own words."""
    if at is None:
        return fallback
    return sim_ago(at, context["page"])


@register.filter
def is_mine(message_view: MessageView) -> bool:
    return message_view.message.by_self
