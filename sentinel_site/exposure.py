"""A server that listens beyond the machine never starts without a control token.

On a loopback address only this machine's programs reach the control API, and the defaults
(no token) keep the README's examples one command. Listening on any other address without
`SENTINEL_CONTROL_TOKEN` would let anyone who can reach the port create, drive and grade runs,
so a token is made up at start and printed (once, to the person starting the server).

    python -m sentinel_site.exposure HOST   # what `./dev serve` runs: prints `export …` lines
"""

from __future__ import annotations

import ipaddress
import os
import secrets
import shlex
import sys

LOOPBACK_NAMES = ("localhost",)


def is_loopback(host: str) -> bool:
    if host in LOOPBACK_NAMES:
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:
        return False  # a name other than localhost: it may resolve anywhere


def control_token_for(host: str, environ: dict[str, str]) -> str | None:
    """A fresh control token when `host` is not loopback and none is configured, else None."""
    if is_loopback(host) or environ.get("SENTINEL_CONTROL_TOKEN", "").strip():
        return None
    return secrets.token_urlsafe(24)


def announcement(host: str, token: str) -> str:
    return (
        f"listening on {host}, beyond this machine: control token generated for this server, "
        f"send 'Authorization: Bearer {token}' to the control API "
        "(set SENTINEL_CONTROL_TOKEN to choose it; SENTINEL_ALLOWED_HOSTS to the names clients use)"
    )


def main(argv: list[str]) -> int:
    if len(argv) != 1:
        print("usage: python -m sentinel_site.exposure HOST", file=sys.stderr)
        return 2
    token = control_token_for(argv[0], dict(os.environ))
    if token:
        print(announcement(argv[0], token), file=sys.stderr)
        print(f"export SENTINEL_CONTROL_TOKEN={shlex.quote(token)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
