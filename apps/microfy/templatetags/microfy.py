"""MicroFy's template helpers: shelves of cards and song rows rendered once per distinct input
(apps.kit.fragments), the player's clock text and the audio clip of a track."""

from __future__ import annotations

from django import template
from django.utils.safestring import SafeString, mark_safe

from apps.kit.fragments import render_fragment
from apps.kit.retractions import present
from apps.media.links import audio_url
from apps.microfy.state import Track, clock_text

register = template.Library()


@register.filter
def clock(seconds: float) -> str:
    """`203` → `"3:23"`."""
    return clock_text(seconds)


@register.simple_tag
def audio_src(track_id: str) -> str:
    """The generated clip the player plays for a track."""
    return audio_url(f"microfy {track_id}")


def _shared(context: template.Context) -> dict:
    return {"root": context["root"], "back": context["here"], "csrf_token": context["csrf_token"]}


@register.simple_tag(takes_context=True)
def track_cards(
    context: template.Context, tracks: tuple[Track, ...], new: bool = False
) -> SafeString:
    """A shelf's square cards (microfy/_card.html), each rendered once per distinct input; an
    unavailable track has no card (a shelf offers only what plays)."""
    shared = _shared(context)
    cards = (
        render_fragment("microfy/_card.html", track=t, new=new, **shared) for t in present(tracks)
    )
    return mark_safe("".join(cards))


@register.simple_tag(takes_context=True)
def track_rows(context: template.Context, rows, show_album: bool = True) -> SafeString:
    """Numbered song rows (microfy/_row.html) from `(track, liked)` or `(track, liked, plays)`."""
    shared = _shared(context)
    html = []
    for number, row in enumerate(rows, start=1):
        track, liked, plays = (*row, None) if len(row) == 2 else row
        html.append(
            render_fragment(
                "microfy/_row.html",
                track=track,
                liked=liked,
                plays=plays,
                number=number,
                show_album=show_album,
                **shared,
            )
        )
    return mark_safe("".join(html))
