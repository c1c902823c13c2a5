"""Run creation is rate-limited per client address (finding: runs could be created without
limit). A request presenting the control token (the operator's own tools) is never limited.

The rate is `SENTINEL_RUN_CREATION_RATE` (DRF's form: "1000/min"; "off" for none), counted in
each server process's memory: N processes of the production shape allow N times the rate.
"""

from __future__ import annotations

from django.conf import settings
from rest_framework.exceptions import Throttled
from rest_framework.throttling import SimpleRateThrottle

from apps.control.auth import is_control_authenticated


class RunCreationThrottle(SimpleRateThrottle):
    scope = "run-creation"

    def get_rate(self) -> str | None:
        rate = settings.SENTINEL_RUN_CREATION_RATE
        return None if rate == "off" else rate

    def allow_request(self, request, view) -> bool:
        if is_control_authenticated(request):
            return True
        return super().allow_request(request, view)

    def get_cache_key(self, request, view) -> str:
        return self.cache_format % {"scope": self.scope, "ident": self.get_ident(request)}


def refusal(wait: float | None) -> Throttled:
    again = f"; try again in {wait:.0f} s" if wait is not None else ""
    return Throttled(
        wait,
        detail=(
            f"too many runs created from this address: at most {settings.SENTINEL_RUN_CREATION_RATE} "
            f"(SENTINEL_RUN_CREATION_RATE){again}"
        ),
    )
