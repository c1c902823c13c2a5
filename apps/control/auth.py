"""Control endpoints require SENTINEL_CONTROL_TOKEN when one is configured.

The agent only ever gets its task URL and contact URL; without the token it cannot close,
re-init or evaluate runs (upstream weakness §10.1: an agent could forge its own success).
"""

from __future__ import annotations

import hmac

from django.conf import settings
from rest_framework.permissions import SAFE_METHODS, BasePermission


def presented_token(request) -> str:
    header = request.META.get("HTTP_AUTHORIZATION", "")
    if header.lower().startswith("bearer "):
        return header[7:].strip()
    return request.META.get("HTTP_X_SENTINEL_TOKEN", "").strip()


def has_control_access(request) -> bool:
    """True when no token is configured, or the request presents the configured one."""
    expected = settings.SENTINEL_CONTROL_TOKEN
    if not expected:
        return True
    return hmac.compare_digest(presented_token(request).encode(), expected.encode())


def is_control_authenticated(request) -> bool:
    """True only when a token is configured *and* presented: needed to see scenario internals."""
    expected = settings.SENTINEL_CONTROL_TOKEN
    return bool(expected) and hmac.compare_digest(
        presented_token(request).encode(), expected.encode()
    )


class ControlTokenPermission(BasePermission):
    message = (
        "missing or wrong control token: send 'Authorization: Bearer <SENTINEL_CONTROL_TOKEN>'"
    )

    def has_permission(self, request, view) -> bool:
        return has_control_access(request)


def foreign_origin(request) -> str | None:
    """The other site a browser says sent this request, or None when it came from our own pages
    or from a client that is not a browser (those send no Origin header)."""
    origin = request.META.get("HTTP_ORIGIN")
    if not origin or request.method in SAFE_METHODS:
        return None
    own = f"{request.scheme}://{request.get_host()}"
    if origin == own or origin in settings.CSRF_TRUSTED_ORIGINS:
        return None
    return origin


class SameOriginPermission(BasePermission):
    """A web page on another site cannot drive the control API through its visitor's browser.

    The API has no session, so Django's CSRF protection does not apply, and a form on any site
    could otherwise create or close runs on a server at 127.0.0.1 (a form post is a "simple"
    request: no preflight). Browsers send `Origin` with every such post; other clients (the
    harness, curl, the original benchmark's scripts) send none and are not affected."""

    message = "cross-site request refused: the control API answers its own pages and non-browser clients only"

    def has_permission(self, request, view) -> bool:
        return foreign_origin(request) is None
