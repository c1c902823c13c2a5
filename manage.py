#!/usr/bin/env python
"""Django's command-line utility for Sentinel Environments."""

import os
import sys


def main() -> None:
    os.environ.setdefault("DJANGO_SETTINGS_MODULE", "sentinel_site.settings")
    from django.core.management import execute_from_command_line
    from django.db.utils import InterfaceError, OperationalError

    from sentinel_site.config import ConfigError

    try:
        execute_from_command_line(sys.argv)
    except ConfigError as exc:  # a bad environment variable: one clear line, no traceback
        print(f"configuration error: {exc}", file=sys.stderr)
        sys.exit(2)
    except (OperationalError, InterfaceError) as exc:  # e.g. PostgreSQL not reachable
        reason = (str(exc).strip().splitlines() or [type(exc).__name__])[0]
        print(f"database error: {reason} (check DATABASE_URL)", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
