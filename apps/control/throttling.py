"""Run creation is rate-limited per client address (finding: runs could be created without
limit). A request presenting the control token (the operator's own tools) is never limited.

Every door that creates a run counts: the API's `POST /api/runs/` and the flat `/init` and
`/dev_init`. The rate is `SENTINEL_RUN_CREATION_RATE` (DRF's form: "1000/min"; "off" for none),
counted in each server process's memory: N processes of the production shape allow N times the
rate.

A client is its connection's address (`client_address`). DRF's own identity believed any
`X-Forwarded-For` a client sent, so varying that header got past the limit; the header is read
only when the connection comes from a proxy the operator named (`SENTINEL_TRUSTED_PROXIES`).
"""

from __future__ import annotations

import functools
import ipaddress

from django.conf import settings
from rest_framework.exceptions import Throttled
from rest_framework.throttling import SimpleRateThrottle

from apps.control.auth import is_control_authenticated

Network = ipaddress.IPv4Network | ipaddress.IPv6Network


@functools.cache
def _networks(written: tuple[str, ...]) -> tuple[Network, ...]:
    return tuple(ipaddress.ip_network(network, strict=False) for network in written)


def _is_trusted_proxy(address: str, proxies: tuple[Network, ...]) -> bool:
    try:
        ip = ipaddress.ip_address(address)
    except ValueError:
        return False
    return any(ip in network for network in proxies)


def client_address(request) -> str:
    """Who sent `request`: the address at the other end of its connection.

    Only when that address is one of SENTINEL_TRUSTED_PROXIES is `X-Forwarded-For` read, from
    its right end (the entry the nearest proxy added) leftwards, past every trusted proxy: the
    first address that is not one is the client. Entries further left are the client's own
    words and are never believed."""
    address = request.META.get("REMOTE_ADDR") or ""
    proxies = _networks(tuple(settings.SENTINEL_TRUSTED_PROXIES))
    if not proxies:
        return address
    forwarded = request.META.get("HTTP_X_FORWARDED_FOR", "")
    hops = [hop.strip() for hop in forwarded.split(",") if hop.strip()]
    while hops and _is_trusted_proxy(address, proxies):
        address = hops.pop()
    return address


class RunCreationThrottle(SimpleRateThrottle):
    scope = "run-creation"

    def get_rate(self) -> str | None:
        rate = settings.SENTINEL_RUN_CREATION_RATE
        return None if rate == "off" else rate

    def allow_request(self, request, view) -> bool:
        if is_control_authenticated(request):
            return True
        if not super().allow_request(request, view):
            raise refusal(self.wait())
        return True

    def get_ident(self, request) -> str:
        return client_address(request)

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
