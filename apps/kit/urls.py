"""Agent-site URLs shared by every environment, under the run's prefix (`token` is a URL kwarg)."""

from django.urls import path

from apps.kit import views

urlpatterns = [
    path("", views.run_home, name="run-home"),
    # Also the websocket path (sentinel_site/routing.py): over HTTP, the polling fallback.
    path("live", views.live_poll, name="live-poll"),
]
