"""The home page at `/`: what this server is and where everything lives."""

from __future__ import annotations

from django.conf import settings
from django.http import FileResponse, Http404, HttpRequest, HttpResponse, HttpResponseRedirect
from django.shortcuts import render
from django.views.decorators.http import require_POST

from apps.home import overview
from apps.kit.links import task_path
from apps.scenarios.library import get_dev_scenario
from events import lifecycle
from events.registry import UnknownEnvironment, get_environment


def home(request: HttpRequest) -> HttpResponse:
    # With a token set, runs and their verdicts are a control matter: this public page lists
    # them to a logged-in admin only (an agent's browser can open it, too), and does not say
    # where the scenario files, the answer key, lie on disk.
    runs_hidden = bool(settings.SENTINEL_CONTROL_TOKEN) and not request.user.is_staff
    context = {
        "environments": overview.environment_rows(),
        "scenario_count": overview.scenario_count(),
        "problems": overview.scenario_problems(),
        "runs": [] if runs_hidden else overview.recent_runs(),
        "runs_hidden": runs_hidden,
        "docs": [(slug, title) for slug, (_, title) in overview.DOCS.items()],
        "scenario_dir": None if runs_hidden else settings.SENTINEL_SCENARIO_DIR,
        "browse_needs_staff": bool(settings.SENTINEL_CONTROL_TOKEN),
    }
    return render(request, "home/index.html", context)


@require_POST
def browse(request: HttpRequest, environment: str) -> HttpResponse:
    """A run of the environment's dev scenario (everything preloaded), opened in the browser."""
    if settings.SENTINEL_CONTROL_TOKEN and not request.user.is_staff:
        # Runs are a control operation: with a token set, only admins start them from here.
        return HttpResponse(
            "starting a run needs the control token: log in to the admin first",
            status=403,
            content_type="text/plain",
        )
    try:
        get_environment(environment)
        spec = get_dev_scenario(environment).to_run_spec()
    except (UnknownEnvironment, FileNotFoundError) as error:
        raise Http404(str(error)) from None
    run = lifecycle.create_run(spec)
    return HttpResponseRedirect(task_path(run))


def doc(request: HttpRequest, name: str) -> FileResponse:
    path = overview.doc_path(name)
    if path is None or not path.is_file():
        raise Http404(f"no document {name!r}")
    return FileResponse(open(path, "rb"), content_type="text/plain; charset=utf-8")
