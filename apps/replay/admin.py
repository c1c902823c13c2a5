"""Runs and their logs in the admin. Events are read-only: the log is append-only.

A run has a merged timeline page (scenario events, page views, actions, lifecycle, filterable by
kind, with each fired event's lateness) and, per row, a link to the environment's own pages as
they looked at that log position (time travel, apps.replay.timetravel). Everything here sits
behind the admin site, so it is staff-only; nothing is reachable from a run's /r/<token>/ URLs.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from urllib.parse import urlencode

from django.contrib import admin, messages
from django.core.exceptions import PermissionDenied
from django.core.paginator import Paginator
from django.http import HttpResponse
from django.shortcuts import get_object_or_404
from django.template.response import TemplateResponse
from django.urls import path, reverse
from django.utils.html import format_html, format_html_join

from apps.replay.models import RunVerdict
from apps.replay.records import latest_verdict, record_verdict, replay
from apps.replay.timetravel import environment_path, render_site_at, site_url
from events.models import Event, EventKind, Run

TIMELINE_PAGE = 500  # entries per page of a run's timeline: a huge run renders as fast as a small

# Pages another app adds under a run, at /admin/events/run/<id>/<route> (the task timeline of
# apps.bench): (route, view(request, run, route_kwargs…) → response, URL name). Apps that know
# runs register here, so this app imports none of them.
RUN_PAGES: list[tuple[str, Callable[..., HttpResponse], str, str]] = []


def add_run_page(route: str, view: Callable[..., HttpResponse], name: str, label: str = "") -> None:
    """Serve `view` under every run; with a `label`, the run's page links to it."""
    RUN_PAGES.append((route, view, name, label))


class VerdictInline(admin.TabularInline):
    model = RunVerdict
    fields = (
        "recorded_at",
        "source",
        "success",
        "detail",
        "graded_at_seq",
        "event_count",
        "state_digest",
    )
    readonly_fields = fields
    extra = 0
    can_delete = False
    max_num = 0

    def has_add_permission(self, request, obj=None):
        return False


@admin.register(Run)
class RunAdmin(admin.ModelAdmin):
    list_display = (
        "id",
        "scenario_id",
        "environment",
        "status",
        "verdict",
        "clock_mode",
        "speed_factor",
        "sim_time",
        "created_at",
        "closed_at",
        "timeline_link",
    )
    list_filter = ("status", "environment", "clock_mode")
    search_fields = ("scenario_id", "token")
    readonly_fields = (
        "token",
        "catalog_dir",
        "catalog_hash",
        "created_at",
        "log_size",
        "timeline_link",
    )
    # The log is not inlined here: a run of 100,000 entries took minutes to render. Its
    # timeline page shows it a page at a time.
    inlines = [VerdictInline]
    actions = ["record_verdicts", "replay_runs"]

    def get_queryset(self, request):
        return super().get_queryset(request).defer("scenario")

    @admin.display(description="verdict (last recorded)")
    def verdict(self, run: Run) -> str:
        recorded = latest_verdict(run)
        if recorded is None:
            return "—"
        return "pass" if recorded.success else "fail"

    @admin.display(description="log")
    def log_size(self, run: Run) -> str:
        if run.pk is None:
            return "—"
        return f"{Event.objects.filter(run_id=run.pk).count():,} entries"

    @admin.display(description="timeline")
    def timeline_link(self, run: Run) -> str:
        if run.pk is None:
            return "—"
        links = [
            format_html(
                '<a href="{}">timeline &amp; time travel</a>',
                reverse("admin:events_run_timeline", args=[run.pk]),
            ),
            *(
                format_html('<a href="{}">{}</a>', reverse(f"admin:{name}", args=[run.pk]), label)
                for _, _, name, label in RUN_PAGES
                if label
            ),
        ]
        return format_html_join(" · ", "{}", ((link,) for link in links))

    @admin.action(description="Record the verdict (grade read-only, digest the state)")
    def record_verdicts(self, request, queryset):
        for run in queryset:
            verdict = record_verdict(run, source="admin")
            self.message_user(
                request, f"run {run.pk}: {'pass' if verdict.success else 'fail'} — {verdict.detail}"
            )

    @admin.action(description="Replay: refold from scratch and compare with the record")
    def replay_runs(self, request, queryset):
        for run in queryset:
            report = replay(run)
            if report.recorded is None:
                # Nothing to compare with yet: not a mismatch, a run nobody has graded.
                self.message_user(
                    request,
                    f"run {run.pk}: not graded yet — nothing to compare with; record its "
                    "verdict first (action “Record the verdict”), then replay",
                    messages.WARNING,
                )
            elif report.matches:
                self.message_user(request, f"run {run.pk}: match", messages.SUCCESS)
            else:
                self.message_user(
                    request,
                    f"run {run.pk}: mismatch — {'; '.join(report.differences)}",
                    messages.ERROR,
                )

    def get_urls(self):
        view = self.admin_site.admin_view
        return [
            path("<int:run_id>/timeline/", view(self.timeline_view), name="events_run_timeline"),
            path(
                "<int:run_id>/at/<int:seq>/site/",
                view(self.site_at_view),
                {"page_path": ""},
                name="events_run_site_at_root",
            ),
            path(
                "<int:run_id>/at/<int:seq>/site/<path:page_path>",
                view(self.site_at_view),
                name="events_run_site_at",
            ),
            *(
                path(f"<int:run_id>/{route}", view(self._run_page(page)), name=name)
                for route, page, name, _ in RUN_PAGES
            ),
            *super().get_urls(),
        ]

    def _run_page(self, page: Callable[..., HttpResponse]) -> Callable[..., HttpResponse]:
        def run_page(request, run_id: int, **kwargs):
            run = get_object_or_404(Run, pk=run_id)
            if not self.has_view_permission(request, run):
                raise PermissionDenied
            return page(request, run, self.admin_site.each_context(request), **kwargs)

        return run_page

    def timeline_view(self, request, run_id: int):
        run = get_object_or_404(Run, pk=run_id)
        if not self.has_view_permission(request, run):
            raise PermissionDenied
        kinds = [k for k in request.GET.getlist("kind") if k in EventKind.values] or list(
            EventKind.values
        )
        log = Event.objects.filter(run_id=run.pk, kind__in=kinds).order_by("seq")
        page = Paginator(log, TIMELINE_PAGE).get_page(request.GET.get("page"))
        rows = []
        for event in page.object_list:
            viewed = (
                environment_path(run, event.payload.get("path", ""))
                if event.kind == EventKind.VIEW
                else ""
            )
            rows.append(
                {
                    "event": event,
                    "payload": json.dumps(event.payload, ensure_ascii=False)[:300],
                    "site_url": site_url(run, event.seq, viewed),
                }
            )
        context = {
            **self.admin_site.each_context(request),
            "title": f"Run {run.pk} · {run.scenario_id} — merged timeline",
            "opts": self.model._meta,
            "original": run,
            "run": run,
            "rows": rows,
            "page": page,
            "kind_query": urlencode([("kind", kind) for kind in kinds]),
            "kinds": [(k, k in kinds) for k in EventKind.values],
            "verdict": latest_verdict(run),
            "condition_at": run.condition_at,
        }
        return TemplateResponse(request, "replay/run_timeline.html", context)

    def site_at_view(self, request, run_id: int, seq: int, page_path: str):
        run = get_object_or_404(Run, pk=run_id)
        if not self.has_view_permission(request, run):
            raise PermissionDenied
        return render_site_at(request, run, seq, page_path)


@admin.register(Event)
class EventAdmin(admin.ModelAdmin):
    list_display = ("run", "seq", "at", "kind", "type", "lateness_ms")
    list_filter = ("kind",)

    def has_add_permission(self, request):
        return False

    def has_change_permission(self, request, obj=None):
        return False

    def has_delete_permission(self, request, obj=None):
        return False
