"""The buttons and the comment form under a post in a social feed (MicroDin, MicroGram), as a view
carries them out. Each app still says where the browser goes back to: that differs."""

from __future__ import annotations

from collections.abc import Mapping

from django.http import HttpRequest

from apps.kit.pages import Page, one_of


def act_on_post(
    request: HttpRequest, page: Page, post_id: str, action: str, notices: Mapping[str, str]
) -> str:
    """Carry out a post's button or its comment form: `action` is one of `notices` (a 404 page
    otherwise), which maps each to the toast it shows. Returns that toast."""
    one_of(action, notices, "post action")
    payload = {"post_id": post_id}
    if action == "comment_post":
        payload["text"] = request.POST.get("text", "")
    page.act(action, payload)
    return notices[action]
