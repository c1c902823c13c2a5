"""A URLconf for the request-thread tests: views that report where they ran."""

import threading
import time

from django.db import connection
from django.http import JsonResponse, StreamingHttpResponse
from django.urls import path

_active = 0
_most = 0
_lock = threading.Lock()


def where(request):
    with connection.cursor() as cursor:  # opens this thread's connection if it has none yet
        cursor.execute("SELECT 1")
    return JsonResponse(
        {
            "view_thread": threading.current_thread().name,
            "middleware_thread": request.META.get("middleware_thread"),
            "connection": id(connection.connection),
        }
    )


def slow(request):
    global _active, _most
    with _lock:
        _active += 1
        _most = max(_most, _active)
    time.sleep(0.2)
    with _lock:
        _active -= 1
    return JsonResponse({"most_at_once": _most, "ended": time.time()})


def streamed(request):
    """Content produced while it is sent: each part says which thread made it."""
    return StreamingHttpResponse(f"{threading.current_thread().name}\n" for _ in range(2))


def active() -> int:
    """How many slow views are running now."""
    return _active


def reset_concurrency() -> None:
    global _active, _most
    _active = _most = 0


def arrival(request):
    """When the request arrived (stamped before it waited for a thread) and when it ran."""
    from apps.kit.pages import arrival_wall

    return JsonResponse(
        {
            "arrived": arrival_wall(request),
            "ran": time.time(),
            "view_thread": threading.current_thread().name,
        }
    )


urlpatterns = [
    path("where", where),
    path("streamed", streamed),
    path("slow", slow),
    # Under the run prefix: served on the agents' lane (sentinel_site.http_handler.Lanes).
    path("r/where", where),
    path("r/slow", slow),
    path("r/arrival", arrival),
]
