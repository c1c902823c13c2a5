"""Websocket URL routing: a run's live socket shares its path with the polling fallback."""

from channels.routing import URLRouter
from channels.security.websocket import OriginValidator
from django.conf import settings
from django.urls import path

from apps.kit.consumers import RunLiveConsumer
from sentinel_site.urls import RUN_PREFIX

websocket_urlpatterns = [
    path(f"{RUN_PREFIX}live", RunLiveConsumer.as_asgi()),
]


class BrowserOriginValidator(OriginValidator):
    """A browser's socket is accepted only from a page on one of ALLOWED_HOSTS (a page of
    another site cannot open one through its visitor's browser); a client that is not a
    browser sends no Origin and is accepted, as for HTTP (its token is what admits it)."""

    def valid_origin(self, parsed_origin):
        return parsed_origin is None or self.validate_origin(parsed_origin)


def websocket_application():
    return BrowserOriginValidator(URLRouter(websocket_urlpatterns), settings.ALLOWED_HOSTS)
