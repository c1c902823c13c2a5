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


# What a browser says (Fetch Metadata, `Sec-Fetch-Site`) of a request that came from one of our
# own pages ("same-origin") or from the person at the browser, typing or following a bookmark
# ("none"). Any other value is another site's page: "same-site" included (another port of
# 127.0.0.1 is another program's).
OWN_SITE = ("same-origin", "none")


def cross_site(request, *, reads_too: bool = False) -> str | None:
    """The header by which a browser says another site's page sent this request (e.g.
    "Sec-Fetch-Site: cross-site", "Origin: https://evil.example"), or None when it came from our
    own pages, from an origin the operator trusts (SENTINEL_CSRF_TRUSTED_ORIGINS), or from a
    client that is not a browser: those send neither header.

    Only requests that change something are judged: unsafe methods, and safe ones too when
    `reads_too` (the flat protocol's GETs that advance, start or close the default run)."""
    if request.method in SAFE_METHODS and not reads_too:
        return None
    meta = request.META
    origin = meta.get("HTTP_ORIGIN")
    if origin and origin in settings.CSRF_TRUSTED_ORIGINS:
        return None
    fetched_from = meta.get("HTTP_SEC_FETCH_SITE")
    if fetched_from and fetched_from not in OWN_SITE:
        return f"Sec-Fetch-Site: {fetched_from}"
    if origin and origin != f"{request.scheme}://{request.get_host()}":
        return f"Origin: {origin}"
    return None


def cross_site_refusal(found: str) -> str:
    """The one line a refused cross-site request is answered with."""
    return (
        f"cross-site request refused ({found}): this server's controls answer its own pages "
        "and clients that are not browsers only"
    )


class SameOriginPermission(BasePermission):
    """A web page on another site cannot drive the control API through its visitor's browser.

    The API has no session, so Django's CSRF protection does not apply, and a form on any site
    could otherwise create or close runs on a server at 127.0.0.1 (a form post is a "simple"
    request: no preflight). Browsers say where every such request comes from (`Origin`, and
    `Sec-Fetch-Site` over HTTPS and on loopback); other clients (the harness, curl, the original
    benchmark's scripts) send neither and are not affected. The flat endpoints' GETs that change
    the default run are held to the same rule by `apps.control.slot.flat_endpoint`."""

    message = cross_site_refusal("another site's page")

    def has_permission(self, request, view) -> bool:
        found = cross_site(request)
        if found:
            self.message = cross_site_refusal(found)
        return found is None
