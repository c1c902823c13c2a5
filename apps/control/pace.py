"""The views' side of fast-forward pacing (the pacer itself: sentinel_site/pacing.py).

When every awake place is taken, the pacer first asks the view whether a request is one to hold
back: a fast-forward run's wait (until when, at the latest) or its first task-URL visit. The
view answers with `hold_until(...)`, which never reaches the client: the pacer holds the request
and then sends it again, admitted. Any other answer (a live run's visit, a refused wait) goes
to the client as it is.
"""

from __future__ import annotations

from django.http import HttpRequest, HttpResponse

SCOPE_KEY = "sentinel.pace"  # ASGI scope: what the pacer wants of this pass
ASK = "ask"  # hold_until(...) if the request is one to hold back, else answer it
ADMITTED = "admitted"  # answer it: its turn has come
ASKED_AT = "sentinel.asked_at"  # ASGI scope: the wall time a held request first arrived at
HOLD_HEADER = "X-Sentinel-Hold-Until"  # the wall time to let it go by ("" = no such time)
HELD_HEADER = "X-Sentinel-Held-Ms"  # on the client's answer: how long the request was held


def asked(request: HttpRequest) -> bool:
    """Whether the pacer asks whether to hold this request back (not yet admitted)."""
    scope = getattr(request, "scope", None)
    return isinstance(scope, dict) and scope.get(SCOPE_KEY) == ASK


def asked_at(request: HttpRequest) -> float | None:
    """The wall time an admitted request first arrived at, when it was held back (its arrival,
    `apps.kit.pages.arrival_wall`, is when it was let go); None when it was not held."""
    scope = getattr(request, "scope", None)
    return scope.get(ASKED_AT) if isinstance(scope, dict) else None


def hold_until(wall: float | None) -> HttpResponse:
    """Hold this request back until an awake place is free, or at the latest until wall time
    `wall` (None: no such time)."""
    response = HttpResponse(status=202)
    response[HOLD_HEADER] = "" if wall is None else repr(wall)
    return response
