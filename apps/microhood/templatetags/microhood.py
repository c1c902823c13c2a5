"""Rows and cards rendered once per distinct content (apps.kit.fragments)."""

from django import template

from apps.kit.fragments import render_fragment

register = template.Library()


@register.simple_tag
def side_row(row, root: str):
    return render_fragment("microhood/_row.html", row=row, root=root)


@register.simple_tag
def card(row, root: str):
    return render_fragment("microhood/_card.html", row=row, root=root)
