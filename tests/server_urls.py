"""The URLs of a site server the test suite keeps between tests (`live_site`): the site's own,
and one that makes the server forget what its process remembers about earlier tests.

Each test still starts from an empty database (transactional tests flush it), but a server that
outlives a test keeps per-process memory keyed by run, content type or file: folded states,
rendered screens, live renders, timeline hints, scenario specs, the library, the ticker's view of
live runs and Django's content-type ids (which a flush renumbers). `live_site` posts here before
every test, so a test sees the server as if it had just started. Only a server started by the
test suite with SENTINEL_TEST_SHARED_SERVER=1 (tests/settings.py) has this URL.
"""

from __future__ import annotations

from django.contrib.contenttypes.models import ContentType
from django.http import HttpRequest, HttpResponse, JsonResponse
from django.urls import path
from django.views.decorators.csrf import csrf_exempt
from django.views.decorators.http import require_POST

from apps.kit import live, screen_cache
from apps.scenarios import library
from events import models, projection, scheduler
from events.ticker import ticker
from sentinel_site import pacing
from sentinel_site.urls import urlpatterns as site_urlpatterns

FORGET_PATH = "__tests__/forget"
PACING_PATH = "__tests__/pacing"


@csrf_exempt
@require_POST
def forget(request: HttpRequest) -> HttpResponse:
    """Drop every per-process memory of earlier tests' runs and rows."""
    projection.clear_cache()
    screen_cache.clear()
    live._renders.clear()
    scheduler._next_unfired.clear()
    models._spec_cache.clear()
    library._libraries.clear()
    ContentType.objects.clear_cache()
    pacing.forget_all()
    ticker.wake()  # re-read the live runs now, not up to a second later
    return HttpResponse(status=204)


def pacing_status(request: HttpRequest) -> JsonResponse:
    """Which runs the server's pacer has awake and which it holds back (a test waits on it)."""
    return JsonResponse(pacing.status())


urlpatterns = [path(FORGET_PATH, forget), path(PACING_PATH, pacing_status), *site_urlpatterns]
