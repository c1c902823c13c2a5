"""ASGI entry point: HTTP (Django) + websockets (Channels), and the in-process ticker."""

import os
import sys

os.environ.setdefault("DJANGO_SETTINGS_MODULE", "sentinel_site.settings")

from sentinel_site.config import ConfigError  # noqa: E402

try:
    from django.core.asgi import get_asgi_application

    django_asgi = get_asgi_application()
except ConfigError as exc:  # one clear line, no traceback
    print(f"configuration error: {exc}", file=sys.stderr)
    raise SystemExit(2) from None

from channels.routing import ProtocolTypeRouter  # noqa: E402
from django.conf import settings  # noqa: E402

from events.ticker import ticker  # noqa: E402

router = ProtocolTypeRouter({"http": django_asgi})


async def application(scope, receive, send):
    # Daphne speaks no ASGI lifespan, so the ticker starts with the first connection the app
    # serves (the loop is only reachable from inside a request). Idempotent.
    if settings.SENTINEL_TICKER == "inprocess":
        ticker.ensure_started()
    if scope["type"] == "lifespan":
        return
    await router(scope, receive, send)
