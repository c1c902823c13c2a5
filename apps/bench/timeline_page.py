"""The task timeline in the admin, under its run: /admin/events/run/<id>/task/ (apps.bench.timeline
draws it), and the transcript's screenshots it shows, served from the task's result folder.

A run the harness graded has a TaskResult naming its result set's folder: the transcript, the
screenshots and results.json are read there; the log is read from the database. Any other run
gets the same page from its log alone (no transcript, the last recorded verdict).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from urllib.parse import quote

from django.http import FileResponse, Http404, HttpRequest, HttpResponse
from django.template.response import TemplateResponse
from django.urls import reverse
from django.utils.safestring import mark_safe

from apps.bench.layout import agent_files, trial_folder
from apps.bench.models import TaskResult
from apps.bench.task_trace import trace_of
from apps.bench.timeline import Links, build_timeline, render_timeline
from apps.kit.links import environment_root
from apps.replay.records import latest_verdict
from apps.replay.timetravel import site_url
from events.models import Event, Run
from events.timing import REACTION_WINDOW

PATH_SAFE = "!$&'()*+,;=/~:@"  # as Django's reverse() quotes a <path:> argument
LOG_FIELDS = ("seq", "at", "kind", "type", "payload", "timeline_index")


def task_of(run: Run) -> TaskResult | None:
    """The benchmark task this run played, if the harness recorded one."""
    return (
        TaskResult.objects.filter(run_id=run.pk).select_related("benchmark").order_by("-id").first()
    )


def folder_of(task: TaskResult | None) -> Path | None:
    if task is None or not task.benchmark.results_dir:
        return None
    folder = Path(task.benchmark.results_dir) / task.environment / task.scenario_id
    folder = trial_folder(folder, task.trial)
    return folder if folder.is_dir() else None


def task_timeline_url(run_id: int) -> str:
    return reverse("admin:events_run_task", args=[run_id])


def site_at_maker(run: Run) -> Callable[[int, str], str]:
    """site_url(run, seq, page) for every row, reversing the URL once: a reverse per row was
    two fifths of the page's time."""
    marker = "987654321"
    root = site_url(run, int(marker))  # …/at/<seq>/site/

    def site_at(seq: int, page: str) -> str:
        path, _, query = page.lstrip("/").partition("?")
        url = root.replace(f"/{marker}/", f"/{seq}/", 1) + quote(path, safe=PATH_SAFE)
        return url + (f"?{query}" if query else "")

    return site_at


def task_timeline_view(request: HttpRequest, run: Run, admin_context: dict) -> HttpResponse:
    task = task_of(run)
    rows = Event.objects.filter(run_id=run.pk).order_by("seq").values(*LOG_FIELDS)
    played = {"speed_factor": run.speed_factor, "clock_mode": run.clock_mode}
    trace = trace_of(run.spec, rows, played, folder_of(task))
    recorded = None if trace.result else latest_verdict(run)
    window = (task.benchmark.config or {}).get("reaction_window") if task else None
    timeline = build_timeline(
        trace,
        title=run.scenario_id,
        environment_root=environment_root(run),
        window=float(window or REACTION_WINDOW),
        recorded=recorded.as_dict() if recorded else None,
    )
    files = reverse("admin:events_run_task_file", args=[run.pk, "x"])[:-1]
    links = Links(site_at=site_at_maker(run), screenshot=lambda name: files + name)
    context = {
        **admin_context,
        "title": f"Run {run.pk} · {run.scenario_id} — task timeline",
        "run": run,
        "task": task,
        "opts": Run._meta,
        "timeline_html": mark_safe(render_timeline(timeline, links)),  # escaped as it is built
    }
    return TemplateResponse(request, "bench/task_timeline.html", context)


def task_file_view(request: HttpRequest, run: Run, admin_context: dict, name: str) -> HttpResponse:
    """A file the task's agent left (a transcript screenshot), never one outside its files."""
    folder = folder_of(task_of(run))
    if folder is None:
        raise Http404("this run has no benchmark task folder")
    folder = agent_files(folder)
    target = (folder / name).resolve()
    if not target.is_relative_to(folder.resolve()) or not target.is_file():
        raise Http404(f"no file {name!r} in this task's folder")
    return FileResponse(open(target, "rb"))
