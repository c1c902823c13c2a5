"""An item's buttons and small forms (a track's, an artist's, a video's), as a view carries them
out: the action named in the URL, on the item the URL names, with the few fields its form posts."""

from __future__ import annotations

from collections.abc import Mapping

from django.http import HttpRequest

from apps.kit.pages import Page, one_of


def act_on_item(
    request: HttpRequest,
    page: Page,
    action: str,
    notices: Mapping[str, str],
    key: str,
    item_id: str,
    forms: Mapping[str, tuple[str, ...]] | None = None,
) -> str:
    """Carry out `action` — one of `notices` (a 404 page otherwise), which maps each to the toast
    it shows — with the payload `{key: item_id}` and the fields `forms[action]` as posted (empty
    when missing). Returns that toast."""
    one_of(action, notices, f"{key.removesuffix('_id')} action")
    payload = {key: item_id}
    for field in (forms or {}).get(action, ()):
        payload[field] = request.POST.get(field, "")
    page.act(action, payload)
    return notices[action]
