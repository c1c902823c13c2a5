"""Websocket URL routing: a run's live socket shares its path with the polling fallback."""

from django.urls import path

from apps.kit.consumers import RunLiveConsumer
from sentinel_site.urls import RUN_PREFIX

websocket_urlpatterns = [
    path(f"{RUN_PREFIX}live", RunLiveConsumer.as_asgi()),
]
