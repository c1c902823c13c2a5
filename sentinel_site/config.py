"""Small validating readers for environment variables.

Every setting that comes from the environment goes through one of these, so a typo in
configuration stops start-up with one line naming the variable and what it accepts,
instead of surfacing later as a confusing runtime error.
"""

from __future__ import annotations

import ipaddress
import os
from pathlib import Path
from urllib.parse import unquote, urlsplit

from django.core.exceptions import ImproperlyConfigured


class ConfigError(ImproperlyConfigured):
    """A bad environment variable; the message is one line meant for a human."""


def env_str(name: str, default: str = "") -> str:
    return os.environ.get(name, default).strip()


def env_choice(name: str, choices: tuple[str, ...], default: str) -> str:
    value = env_str(name, default).lower()
    if value not in choices:
        raise ConfigError(f"{name}={value!r} is not valid; allowed: {', '.join(choices)}")
    return value


def env_bool(name: str, default: bool = False) -> bool:
    raw = env_str(name, "1" if default else "0").lower()
    if raw in ("1", "true", "yes", "on"):
        return True
    if raw in ("0", "false", "no", "off", ""):
        return False
    raise ConfigError(f"{name}={raw!r} is not a boolean; allowed: 1/0, true/false, yes/no, on/off")


def env_int(name: str, default: int, *, minimum: int = 0) -> int:
    raw = env_str(name, str(default))
    try:
        value = int(raw)
    except ValueError:
        raise ConfigError(f"{name}={raw!r} is not a whole number") from None
    if value < minimum:
        raise ConfigError(f"{name}={value} is too small; the least allowed is {minimum}")
    return value


def env_rate(name: str, default: str) -> str:
    """A rate as "<count>/<second|minute|hour|day>" (or its first letter, as DRF reads it), or
    "off"."""
    value = env_str(name, default).lower()
    count, _, period = value.partition("/")
    if value == "off" or (
        count.isdigit() and int(count) > 0 and period[:1] in ("s", "m", "h", "d")
    ):
        return value
    raise ConfigError(f"{name}={value!r} is not a rate; write e.g. 1000/min, 20/s, or off")


def env_networks(name: str) -> tuple[str, ...]:
    """Comma-separated IP addresses or networks ("10.0.0.5", "10.0.0.0/8", "::1"), each as
    written; none when unset."""
    found = tuple(part.strip() for part in env_str(name).split(",") if part.strip())
    for part in found:
        try:
            ipaddress.ip_network(part, strict=False)
        except ValueError:
            raise ConfigError(
                f"{name}: {part!r} is not an IP address or network; write e.g. 10.0.0.5,10.1.0.0/16"
            ) from None
    return found


def env_dir(name: str, default: Path, *, base: Path) -> Path:
    """A directory that must exist (relative paths are taken from the project root)."""
    raw = env_str(name)
    path = Path(raw) if raw else default
    if not path.is_absolute():
        path = (base / path).resolve()
    if not path.is_dir():
        raise ConfigError(f"{name}={str(path)!r} is not an existing directory")
    return path


def env_url(name: str, default: str, *, schemes: tuple[str, ...]) -> str:
    value = env_str(name, default)
    if not value:
        return ""
    scheme = urlsplit(value).scheme
    if scheme not in schemes:
        raise ConfigError(
            f"{name}={value!r} has scheme {scheme!r}; allowed: {', '.join(s + '://' for s in schemes)}"
        )
    return value


# Connections are kept for the life of their thread (CONN_MAX_AGE=None). Page requests run on a
# few long-lived threads (sentinel_site/http_handler.py), so a kept connection is reused by
# every request on its thread; opening one per request was a tenth of a page's cost on SQLite
# and more on PostgreSQL.


def database_from_url(name: str, url: str, *, base: Path) -> dict:
    """Translate `sqlite:///relative/path`, `sqlite:////abs/path` or `postgres://…` to Django."""
    parts = urlsplit(url)
    if parts.scheme == "sqlite":
        raw_path = unquote(parts.path)[1:] if parts.path.startswith("/") else unquote(parts.path)
        if not raw_path:
            raise ConfigError(f"{name}={url!r} names no file; use sqlite:///var/db.sqlite3")
        path = Path(raw_path)
        if not path.is_absolute():
            path = base / path
        path.parent.mkdir(parents=True, exist_ok=True)
        return {
            "ENGINE": "django.db.backends.sqlite3",
            "NAME": str(path),
            "OPTIONS": {
                # WAL lets readers proceed while one writer appends; IMMEDIATE takes the write
                # lock up front so concurrent appenders queue on the busy timeout instead of
                # failing with "database is locked" when upgrading a read transaction.
                "init_command": "PRAGMA journal_mode=WAL; PRAGMA synchronous=NORMAL;",
                "transaction_mode": "IMMEDIATE",
                "timeout": 30,
            },
            # A file (not :memory:) so WAL and threads work in tests; one per process so
            # concurrent test sessions on one checkout never share it.
            "CONN_MAX_AGE": None,  # kept connections: see above
            "TEST": {"NAME": str(path.with_name(f"test_{os.getpid()}_{path.name}"))},
        }
    if parts.scheme in ("postgres", "postgresql"):
        db_name = unquote(parts.path.lstrip("/"))
        if not db_name:
            raise ConfigError(f"{name}={url!r} names no database")
        return {
            "ENGINE": "django.db.backends.postgresql",
            "NAME": db_name,
            "USER": unquote(parts.username or ""),
            "PASSWORD": unquote(parts.password or ""),
            "HOST": parts.hostname or "",
            "PORT": str(parts.port or ""),
            "CONN_MAX_AGE": None,  # kept connections: see above
            "CONN_HEALTH_CHECKS": True,  # a server restarted under us costs one retry, not a 500
            "TEST": {"NAME": f"test_{db_name}_{os.getpid()}"},
        }
    raise ConfigError(
        f"{name}={url!r} has scheme {parts.scheme!r}; allowed: sqlite://, postgres://"
    )
