"""The template tags render exactly the documented <img> markup, labels only ever escaped."""

from __future__ import annotations

import pytest
from django.template import Context, Template, TemplateSyntaxError


def render(source: str, **context) -> str:
    return Template("{% load media %}" + source).render(Context(context))


def test_avatar_is_a_decorative_image_of_the_given_size():
    assert render('{% avatar "Maya Okonjo" size=40 %}') == (
        '<img class="avatar" src="/media/avatars/maya-okonjo.svg" alt="" width="40" height="40">'
    )


def test_avatar_defaults_to_32_pixels_and_takes_a_variable():
    html = render("{% avatar name %}", name="Chris Taylor")
    assert 'src="/media/avatars/chris-taylor.svg"' in html
    assert 'width="32" height="32"' in html


def test_a_label_becomes_the_alt_text():
    html = render('{% avatar "Maya Okonjo" label="Maya Okonjo" %}')
    assert 'alt="Maya Okonjo"' in html


def test_logo_banner_and_picture_markup():
    assert render('{% logo "Acme Robotics" %}') == (
        '<img class="logo" src="/media/logos/acme-robotics.svg" alt="" width="40" height="40">'
    )
    assert render('{% banner "Maya Okonjo" %}') == (
        '<img class="banner" src="/media/banners/maya-okonjo.svg" alt="" width="1200" height="300">'
    )
    assert render(
        '{% picture "post 7" subject="food" width=240 height=160 label="Lunch at the office" %}'
    ) == (
        '<img class="picture" src="/media/pictures/food/post-7.svg" alt="Lunch at the office"'
        ' width="240" height="160">'
    )


def test_picture_defaults_to_a_480_by_320_landscape():
    assert render('{% picture "post 7" %}') == (
        '<img class="picture" src="/media/pictures/landscape/post-7.svg" alt=""'
        ' width="480" height="320">'
    )


def test_extra_classes_are_added():
    assert 'class="avatar small"' in render('{% avatar "Maya" class="small" %}')


def test_names_and_labels_are_escaped():
    nasty = "Eve <script>&\"'> Mallory"
    html = render("{% avatar name label=name %}{% picture name label=name %}", name=nasty)
    assert "<script>" not in html
    assert 'alt="Eve &lt;script&gt;&amp;&quot;&#x27;&gt; Mallory"' in html
    assert 'src="/media/avatars/eve-script-mallory.svg"' in html


def test_an_unknown_subject_is_a_template_error_naming_the_subjects():
    with pytest.raises(TemplateSyntaxError, match="allowed landscape, city, food"):
        render('{% picture "post 7" subject="selfie" %}')


def test_a_size_must_be_a_positive_number():
    with pytest.raises(TemplateSyntaxError, match="width must be a positive number"):
        render('{% avatar "Maya" size="big" %}')
