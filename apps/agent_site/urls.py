"""Agent-site URLs shared by every environment, under /r/<token>/ (`token` is a URL kwarg)."""

from django.urls import path

from apps.agent_site import views

urlpatterns = [
    # Also the websocket path (events.routing): the same URL over HTTP is the polling fallback.
    path("live", views.live_poll, name="live-poll"),
]
