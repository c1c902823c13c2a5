"""The run's own URLs that every environment shares: its home, and the polling fallback of live
pages, `GET /r/<token>/live?url=<page URL>&seq=<N>&due=<simulated seconds or empty>`.

Same answer as the websocket push (apps.kit.consumers), over plain HTTP, for browsers whose
socket cannot connect: 204 when the run's log has no scenario/action event after `seq` and the
run's clock has not reached `due` (when the page's content next changes with the clock), else
`{"type": "regions", "url": …, "seq": M, "next_change": <the new due or null>, "html": <out-of-band
swaps>}`. A pure read: nothing is logged; the render is shared with the sockets (apps.kit.live).
"""

from __future__ import annotations

import math

from django.http import Http404, HttpRequest, HttpResponse, HttpResponseRedirect, JsonResponse
from django.views.decorators.http import require_GET

from apps.kit import live
from apps.kit.links import environment_root
from apps.kit.pages import Page, run_for_token, run_page
from events.clock import sim_now, wall_now
from events.scheduler import fire_due


@require_GET
def run_home(request: HttpRequest, token: str) -> HttpResponse:
    """/r/<token>/ is the environment's home page (a bare prefix would be a dead end)."""
    return HttpResponseRedirect(environment_root(run_for_token(token)) + "/")


@run_page
def no_such_page(request: HttpRequest, page: Page, environment: str, rest: str) -> HttpResponse:
    """Any other address under an environment: the run's own "does not exist" page, in the site's
    shell with a way back (a link a page got wrong led to Django's bare "Not Found")."""
    raise Http404(f"no page at {page.root}/{rest}")


@require_GET
def live_poll(request: HttpRequest, token: str) -> HttpResponse:
    run = run_for_token(token)
    url = request.GET.get("url", "")
    try:
        live.page_path_for(run, url)
    except live.NotLive as exc:
        return JsonResponse({"detail": f"url: {exc}"}, status=400)
    try:
        since = int(request.GET.get("seq", "0"))
    except ValueError:
        return JsonResponse({"detail": "seq must be an integer log position"}, status=400)
    try:
        due = float(request.GET["due"]) if request.GET.get("due") else None
        if due is not None and not math.isfinite(due):
            raise ValueError(due)
    except ValueError:
        return JsonResponse({"detail": "due must be simulated seconds or empty"}, status=400)
    wall = wall_now()  # the poll's one clock reading
    fire_due(run, wall=wall)  # zero staleness: polling alone (no ticker) still moves a live clock
    now, latest = sim_now(run, wall), live.last_live_seq(run.pk)
    if latest <= since and (due is None or now < due):
        return HttpResponse(status=204)
    try:
        update = live.shared_render(run, url, latest, now, request.get_host())
    except live.NotLive as exc:
        return JsonResponse({"detail": str(exc)}, status=404)
    return JsonResponse(update.message())
