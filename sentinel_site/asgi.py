"""ASGI entry point: HTTP (Django + static files), websockets (Channels), the in-process ticker."""

import gc
import os
import sys

os.environ.setdefault("DJANGO_SETTINGS_MODULE", "sentinel_site.settings")

from sentinel_site.config import ConfigError

try:
    import django

    django.setup(set_prefix=False)  # as get_asgi_application(): ASGI sets it per request
    from sentinel_site import request_limits
    from sentinel_site.http_handler import django_http_application

    request_limits.install()  # bodies, headers, idle and per-client connections, at the socket
    django_http = django_http_application()
except ConfigError as exc:  # one clear line, no traceback
    print(f"configuration error: {exc}", file=sys.stderr)
    raise SystemExit(2) from None

from channels.routing import ProtocolTypeRouter
from django.conf import settings
from django.contrib.staticfiles.handlers import ASGIStaticFilesHandler

from events.ticker import ticker
from sentinel_site.routing import websocket_application

# Everything imported so far lives as long as the server: keep the cyclic collector from
# walking it on every full collection (those walks were the long tail of push latency).
gc.freeze()

router = ProtocolTypeRouter(
    {
        # htmx and the live client are our own static files: served here, so the one Daphne
        # process of the embedded shape needs no separate file server and no CDN.
        "http": ASGIStaticFilesHandler(django_http),
        "websocket": websocket_application(),
    }
)


async def application(scope, receive, send):
    # Daphne speaks no ASGI lifespan, so the ticker starts with the first connection the app
    # serves (the loop is only reachable from inside a request). Idempotent.
    if settings.SENTINEL_TICKER == "inprocess":
        ticker.ensure_started()
    if scope["type"] == "lifespan":
        return
    await router(scope, receive, send)
