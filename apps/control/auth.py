"""Control endpoints require SENTINEL_CONTROL_TOKEN when one is configured.

The agent only ever gets its task URL and contact URL; without the token it cannot close,
re-init or evaluate runs (upstream weakness §10.1: an agent could forge its own success).
"""

from __future__ import annotations

import hmac

from django.conf import settings
from rest_framework.permissions import BasePermission


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
