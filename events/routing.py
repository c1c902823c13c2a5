"""Websocket URL routing (the HTTP URLs are in sentinel_site/urls.py)."""

from django.urls import path

from events.consumers import RunLiveConsumer

websocket_urlpatterns = [
    path("r/<str:token>/live", RunLiveConsumer.as_asgi()),
]
