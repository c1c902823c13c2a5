"""What a person sees of a page: the text the watched-page check compares, and the signature a
live push must change to be sent."""

from __future__ import annotations

from apps.kit.visible import visible_signature, visible_text

PAGE = (
    "<html><head><title>Inbox</title><style>p{}</style></head><body>"
    '<time id="sim-clock">Thu 09:01</time><p class="unread">Budget <b>review</b></p>'
    '<div hidden>secret</div><span aria-hidden="true">Your story</span>'
    '<script>var x = "no";</script><img src="/media/a.svg" alt="A">'
    '<svg><use href="#icon-flag"></use></svg><input name="csrfmiddlewaretoken" value="t1">'
    '<a href="/stories/s2/" aria-label="Next story"></a><form action="/s2/like"></form></body>'
    "</html>"
)


def test_visible_text_is_what_is_read_without_the_clock():
    assert visible_text(PAGE) == "Budget review Your story"


def test_the_signature_sees_the_clock_pictures_icons_styling_and_targets_not_tokens():
    same = PAGE.replace('value="t1"', 'value="t2"').replace('alt="A"', 'alt="B"')
    assert visible_signature(same) == visible_signature(PAGE)
    for changed in (
        PAGE.replace('href="/stories/s2/"', 'href="/stories/s3/"'),  # the arrow leads elsewhere
        PAGE.replace('action="/s2/like"', 'action="/s3/like"'),
        PAGE.replace("09:01", "09:02"),
        PAGE.replace("a.svg", "b.svg"),
        PAGE.replace("icon-flag", "icon-flag-off"),
        PAGE.replace('class="unread"', 'class="read"'),
        PAGE.replace("review", "reviews"),
    ):
        assert visible_signature(changed) != visible_signature(PAGE)
