"""Browse benchmark runs and task results; each result links to the run it graded."""

from __future__ import annotations

from django.contrib import admin
from django.db.models import Count, Q
from django.urls import reverse
from django.utils.html import format_html

from apps.bench.models import BenchmarkRun, TaskResult
from apps.bench.timeline_page import task_file_view, task_timeline_view
from apps.replay.admin import add_run_page


def _run_link(result: TaskResult) -> str:
    if result.run_id is None:
        return "—"
    return format_html(
        '<a href="{}">run {}</a> · <a href="{}">timeline</a>',
        reverse("admin:events_run_change", args=[result.run_id]),
        result.run_id,
        reverse("admin:events_run_task", args=[result.run_id]),
    )


class TaskResultInline(admin.TabularInline):
    model = TaskResult
    fields = (
        "scenario_id",
        "trial",
        "environment",
        "category",
        "success",
        "reaction_time",
        "cost_usd",
        "run_link",
        "error",
    )
    readonly_fields = fields
    extra = 0
    can_delete = False
    show_change_link = True

    def has_add_permission(self, request, obj=None):
        return False

    @admin.display(description="run")
    def run_link(self, result):
        return _run_link(result)


@admin.register(BenchmarkRun)
class BenchmarkRunAdmin(admin.ModelAdmin):
    list_display = (
        "name",
        "agent",
        "speed_factor",
        "started_at",
        "finished_at",
        "task_count",
        "passed",
    )
    search_fields = ("name",)
    list_filter = ("agent", "speed_factor")
    readonly_fields = (
        "name",
        "config",
        "agent",
        "speed_factor",
        "results_dir",
        "started_at",
        "finished_at",
    )
    inlines = [TaskResultInline]

    def get_queryset(self, request):
        return (
            super()
            .get_queryset(request)
            .annotate(
                n_tasks=Count("tasks"), n_passed=Count("tasks", filter=Q(tasks__success=True))
            )
        )

    @admin.display(description="tasks", ordering="n_tasks")
    def task_count(self, run):
        return run.n_tasks

    @admin.display(description="passed", ordering="n_passed")
    def passed(self, run):
        return run.n_passed


@admin.register(TaskResult)
class TaskResultAdmin(admin.ModelAdmin):
    list_display = (
        "scenario_id",
        "trial",
        "benchmark",
        "environment",
        "category",
        "success",
        "reaction_time",
        "cost_usd",
        "run_link",
        "has_error",
    )
    list_filter = ("benchmark", "environment", "category", "success")
    search_fields = ("scenario_id", "benchmark__name")
    readonly_fields = [f.name for f in TaskResult._meta.fields] + ["run_link"]

    @admin.display(description="run")
    def run_link(self, result):
        return _run_link(result)

    @admin.display(description="harness error", boolean=True)
    def has_error(self, result):
        return bool(result.error)


# The task timeline, under each run in the admin (apps.replay.admin serves it there).
add_run_page("task/", task_timeline_view, "events_run_task", "task timeline")
add_run_page("task/file/<path:name>", task_file_view, "events_run_task_file")
