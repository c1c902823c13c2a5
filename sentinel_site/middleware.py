"""Django's stock middleware, declared synchronous so that under ASGI it runs as one chain.

Each stock middleware is async-capable through `MiddlewareMixin`, which under ASGI runs every
`process_request` / `process_response` in a worker thread of its own hop: about fourteen
thread switches per request, which on agent pages cost more than rendering. Declared sync-only,
the chain is adapted once and runs in the request's one worker thread, next to the
(synchronous) views. Behaviour is Django's own: these classes change nothing but that flag.
"""

from __future__ import annotations

from django.contrib.auth.middleware import AuthenticationMiddleware
from django.contrib.messages.middleware import MessageMiddleware
from django.contrib.sessions.middleware import SessionMiddleware
from django.middleware.clickjacking import XFrameOptionsMiddleware
from django.middleware.common import CommonMiddleware
from django.middleware.csrf import CsrfViewMiddleware
from django.middleware.security import SecurityMiddleware
from django_htmx.middleware import HtmxMiddleware


def _sync_only(middleware: type) -> type:
    return type(middleware.__name__, (middleware,), {"async_capable": False, "__module__": __name__})


Security = _sync_only(SecurityMiddleware)
Session = _sync_only(SessionMiddleware)
Common = _sync_only(CommonMiddleware)
Csrf = _sync_only(CsrfViewMiddleware)
Authentication = _sync_only(AuthenticationMiddleware)
Messages = _sync_only(MessageMiddleware)
XFrameOptions = _sync_only(XFrameOptionsMiddleware)
Htmx = _sync_only(HtmxMiddleware)
