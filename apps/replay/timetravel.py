"""Time travel: an environment's own pages, rendered as of one log position, for staff only.

The admin URL `/admin/events/run/<id>/at/<seq>/site/<path>` resolves `<path>` against the
environment's urlconf and calls its view with `request.sentinel_time_travel` set; `@run_page`
then folds `state_at(run, seq)` and renders read-only (no view logged, no action performed).
The shell leaves out the live-update client on a read-only page (templates/site/base.html: it
would subscribe to the run's *current* log); the response gets a banner and its POST forms
disabled, so nothing on the page can reach the live run.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from django.http import Http404, HttpRequest, HttpResponse, HttpResponseNotAllowed
from django.urls import Resolver404, resolve, reverse
from django.utils.html import format_html

from apps.kit.links import environment_root
from events.models import Event, Run
from events.registry import UnknownEnvironment, get_environment


@dataclass(frozen=True)
class TimeTravel:
    run: Run
    seq: int
    at: float
    root: str  # what Page.root returns: URL prefix of the environment's pages in the viewer


def site_url(run: Run, seq: int, path: str = "") -> str:
    """The viewer URL of environment page `path` (e.g. "compose?mode=new") at log position `seq`."""
    page, _, query = path.lstrip("/").partition("?")
    if page:
        url = reverse("admin:events_run_site_at", args=[run.pk, seq, page])
    else:
        url = reverse("admin:events_run_site_at_root", args=[run.pk, seq])
    return url + (f"?{query}" if query else "")


def environment_path(run: Run, full_path: str) -> str:
    """A logged view path (/r/<token>/<env>/x?y) relative to the environment root (x?y)."""
    prefix = environment_root(run) + "/"
    return full_path[len(prefix) :] if full_path.startswith(prefix) else ""


_BODY = re.compile(r"<body[^>]*>", re.IGNORECASE)

_DISABLE_FORMS = """<script>
document.addEventListener("DOMContentLoaded", function freeze() {
  document.querySelectorAll("form").forEach(function (form) {
    if ((form.getAttribute("method") || "get").toLowerCase() !== "post") return;
    form.setAttribute("action", "#read-only");
    form.addEventListener("submit", function (e) { e.preventDefault(); e.stopImmediatePropagation(); }, true);
    form.querySelectorAll("button, input, select, textarea").forEach(function (el) { el.disabled = true; });
  });
});
document.addEventListener("htmx:afterSwap", function () { document.dispatchEvent(new Event("DOMContentLoaded")); });
</script>"""


def banner(travel: TimeTravel, timeline_url: str) -> str:
    return format_html(
        '<div id="time-travel-banner" role="status" style="position:sticky;top:0;z-index:9999;'
        'background:#7a1f1f;color:#fff;padding:.5rem 1rem;font:14px/1.4 system-ui,sans-serif">'
        "Time travel — run {} as of log position #{} (t = {} s). Read-only: nothing here is "
        'logged or performed. <a href="{}" style="color:#fff;text-decoration:underline">Back to '
        "the run's timeline</a></div>",
        travel.run.pk,
        travel.seq,
        f"{travel.at:.2f}",
        timeline_url,
    )


def render_site_at(request: HttpRequest, run: Run, seq: int, path: str) -> HttpResponse:
    if request.method != "GET":
        return HttpResponseNotAllowed(["GET"])
    try:
        environment = get_environment(run.environment)
    except UnknownEnvironment:
        raise Http404("this run's environment is not installed") from None
    if not environment.urlconf:
        raise Http404("this environment has no pages")
    last = (
        Event.objects.filter(run_id=run.pk).order_by("-seq").values_list("seq", flat=True).first()
        or 0
    )
    if not 0 <= seq <= last:
        raise Http404(f"log position must be between 0 and {last}")
    event = Event.objects.filter(run_id=run.pk, seq=seq).values_list("at", flat=True).first()
    try:
        match = resolve("/" + path, urlconf=environment.urlconf)
    except Resolver404:
        raise Http404("no such page in this environment") from None
    travel = TimeTravel(
        run=run, seq=seq, at=float(event or 0.0), root=site_url(run, seq).rstrip("/")
    )
    request.sentinel_time_travel = travel
    response = match.func(request, run.token, *match.args, **match.kwargs)
    if hasattr(response, "render") and not getattr(response, "is_rendered", True):
        response = response.render()
    if response.get("Content-Type", "").startswith("text/html") and not response.streaming:
        html = response.content.decode(response.charset or "utf-8")
        timeline_url = reverse("admin:events_run_timeline", args=[run.pk])
        if _BODY.search(html):
            html = _BODY.sub(
                lambda m: m.group(0) + banner(travel, timeline_url) + _DISABLE_FORMS, html, count=1
            )
        response.content = html.encode(response.charset or "utf-8")
    # Location headers (if a view redirects) point into the viewer, never at the live run.
    if response.has_header("Location"):
        location = response["Location"]
        live_root = environment_root(run) + "/"
        if location.startswith(live_root):
            response["Location"] = travel.root + "/" + location[len(live_root) :]
    response["X-Robots-Tag"] = "noindex"
    response["Cache-Control"] = "no-store"
    return response
