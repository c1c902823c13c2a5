"""Icons are inline SVG drawn from one sprite per page: visible without emoji fonts, and small."""

from __future__ import annotations

import pytest
from django.template import Context, Template, TemplateSyntaxError


def test_an_icon_is_a_use_of_its_symbol_decorative_unless_labelled():
    html = Template('{% load icons %}{% icon "flag" size=14 class="filled" %}').render(Context())
    assert html == (
        '<svg class="lucide filled" width="14" height="14" aria-hidden="true">'
        '<use href="#icon-flag"></use></svg>'
    )
    labelled = Template('{% load icons %}{% icon "pin" label="Pinned" %}').render(Context())
    assert 'role="img" aria-label="Pinned"' in labelled


def test_an_unknown_icon_fails_when_the_template_is_compiled():
    with pytest.raises(TemplateSyntaxError, match="lucide has no icon named 'no-such-icon'"):
        Template('{% load icons %}{% icon "no-such-icon" %}')
