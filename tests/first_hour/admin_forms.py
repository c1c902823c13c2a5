"""What a browser would post for an admin change form: every field with its shown value."""

from __future__ import annotations

from typing import Any


def _bound_values(form) -> dict[str, Any]:
    data: dict[str, Any] = {}
    for bound in form:
        value = bound.value()  # already as the widget shows it (JSON as text)
        if value is None or value is False:
            continue
        data[bound.html_name] = "on" if value is True else value
    return data


def change_form_data(response) -> dict[str, Any]:
    """The POST body of the change form in `response`, as rendered (unchanged)."""
    data = _bound_values(response.context["adminform"].form)
    for inline in response.context["inline_admin_formsets"]:
        formset = inline.formset
        data.update(_bound_values(formset.management_form))
        for form in formset.forms:
            data.update(_bound_values(form))
    return data
