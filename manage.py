#!/usr/bin/env python
"""Django's command-line utility for Sentinel Environments."""

import os
import sys


def main() -> None:
    os.environ.setdefault("DJANGO_SETTINGS_MODULE", "sentinel_site.settings")
    from django.core.management import execute_from_command_line

    from sentinel_site.config import ConfigError

    try:
        execute_from_command_line(sys.argv)
    except ConfigError as exc:  # a bad environment variable: one clear line, no traceback
        print(f"configuration error: {exc}", file=sys.stderr)
        sys.exit(2)


if __name__ == "__main__":
    main()
