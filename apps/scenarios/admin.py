"""Scenario authoring in the admin: timeline inline, validation, dry run, chart, actions."""

from __future__ import annotations

import io
import zipfile

from django import forms
from django.contrib import admin, messages
from django.http import HttpResponse, HttpResponseRedirect
from django.shortcuts import get_object_or_404
from django.template.response import TemplateResponse
from django.urls import path, reverse

from apps.kit.links import task_path
from apps.scenarios.chart import timeline_svg
from apps.scenarios.dry_run import dry_run, validate_timeline_entry
from apps.scenarios.format import ScenarioError
from apps.scenarios.library import scenario_problems
from apps.scenarios.models import Scenario, TimelineEvent
from apps.scenarios.reference import eval_sql_problem, evaluation_tables, event_types
from apps.scenarios.serialization import parsed_scenario, run_spec, scenario_text, timeline_of
from apps.scenarios.sync import (
    ScenarioFileError,
    delete_file,
    file_conflict,
    path_problem,
    sync_from_files,
    write_through,
)
from events import lifecycle
from events.registry import UnknownEnvironment, all_environments, get_environment
from events.schemas import schema_fields


class NoopFilter(admin.SimpleListFilter):
    title = "no-op"
    parameter_name = "noop"

    def lookups(self, request, model_admin):
        return (("yes", "no-op (condition_at empty)"), ("no", "has a condition"))

    def queryset(self, request, queryset):
        if self.value() == "yes":
            return queryset.filter(condition_at__isnull=True, is_dev=False)
        if self.value() == "no":
            return queryset.filter(condition_at__isnull=False)
        return queryset


def payload_help(event_types) -> str:
    """What each event type does and the payload it takes, for the author editing a timeline."""
    return " · ".join(
        f"{name}: {event_type.help or 'no description'} — payload "
        + (
            ", ".join(
                f"{field.name} ({field.description}{'' if field.required else ', optional'})"
                for field in schema_fields(event_type.schema)
            )
            or "{}"
        )
        for name, event_type in sorted(event_types.items())
    )


class TimelineEventForm(forms.ModelForm):
    environment: str | None = None  # set per request by TimelineEventInline.get_formset

    class Meta:
        model = TimelineEvent
        fields = ("position", "time", "type", "payload")

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        try:
            event_types = get_environment(self.environment).event_types if self.environment else {}
        except UnknownEnvironment:
            event_types = {}
        if event_types:
            current = self.initial.get("type") or (self.instance.type if self.instance.pk else "")
            choices = [(name, name) for name in sorted(event_types)]
            if current and current not in event_types:
                choices.append((current, f"{current} (not registered)"))
            self.fields["type"] = forms.ChoiceField(choices=choices)
            self.fields["payload"].help_text = payload_help(event_types)

    def clean_time(self):
        time = self.cleaned_data["time"]
        if time is not None and time < 0:
            raise forms.ValidationError("time must be >= 0 seconds")
        return time

    def clean(self):
        cleaned = super().clean()
        if self.environment and "type" in cleaned and "payload" in cleaned:
            problems = validate_timeline_entry(
                self.environment, cleaned["type"], cleaned["payload"]
            )
            if problems:
                self.add_error("payload", "; ".join(problems))
        return cleaned


class TimelineEventInline(admin.TabularInline):
    model = TimelineEvent
    form = TimelineEventForm
    fields = ("position", "time", "type", "payload")
    extra = 0
    ordering = ("position", "id")

    def get_formset(self, request, obj=None, **kwargs):
        environment = obj.environment if obj is not None else None
        form = type("BoundTimelineEventForm", (TimelineEventForm,), {"environment": environment})
        return super().get_formset(request, obj, form=form, **kwargs)


class ScenarioForm(forms.ModelForm):
    class Meta:
        model = Scenario
        fields = "__all__"  # noqa: DJ007 - the admin's fieldsets choose what is shown

    def clean(self):
        cleaned = super().clean()
        end, kill_at, condition_at = (
            cleaned.get(k) for k in ("event_timeline_end", "kill_at", "condition_at")
        )
        if end is not None and kill_at is not None and not 0 < kill_at <= end:
            self.add_error("kill_at", f"must satisfy 0 < kill_at <= event_timeline_end ({end:g})")
        if condition_at is not None and kill_at is not None and not 0 < condition_at <= kill_at:
            self.add_error(
                "condition_at",
                f"must be empty (no-op) or satisfy 0 < condition_at <= kill_at ({kill_at:g})",
            )
        if (
            condition_at is not None
            and not (cleaned.get("eval_sql") or "").strip()
            and not cleaned.get("is_dev")
        ):
            self.add_error("eval_sql", "is required unless condition_at is empty (no-op)")
        environment, path = cleaned.get("environment"), cleaned.get("path")
        if path:
            problem = path_problem(path, environment or "")
            if problem:
                self.add_error("path", problem)
            else:
                # Never overwrite a file changed on disk since this row was read, nor another
                # file (a new row, or a row moved to a new path).
                moved = self.instance.pk is None or path != self.instance.path
                conflict = file_conflict(Scenario(path=path) if moved else self.instance)
                if conflict:
                    self.add_error(None, conflict)
        sql = cleaned.get("eval_sql") or ""
        if environment and sql.strip() and "eval_sql" not in self.errors:
            problem = eval_sql_problem(environment, sql)
            if problem:
                self.add_error("eval_sql", f"{problem} (checked against the evaluation tables)")
        return cleaned


@admin.register(Scenario)
class ScenarioAdmin(admin.ModelAdmin):
    form = ScenarioForm
    change_form_template = "admin/scenarios/scenario/change_form.html"
    list_display = (
        "scenario_id",
        "environment",
        "monitoring_approach",
        "milestone_type",
        "noop",
        "condition_at",
        "kill_at",
        "path",
    )
    list_filter = ("environment", "monitoring_approach", "milestone_type", NoopFilter, "is_dev")
    search_fields = ("scenario_id", "prompt")
    readonly_fields = ("monitoring_approach", "milestone_type", "updated_at")
    fieldsets = (
        (
            None,
            {
                "fields": (
                    "scenario_id",
                    "environment",
                    "path",
                    "prompt",
                    "start_page",
                    "watch_page",
                )
            },
        ),
        (
            "Timing (authored seconds)",
            {"fields": ("condition_at", "event_timeline_end", "kill_at")},
        ),
        (
            "Evaluation",
            {"fields": ("eval_sql", "taxonomy", "monitoring_approach", "milestone_type")},
        ),
        ("Notes and solution", {"fields": ("annotator_notes", "solution", "is_dev")}),
        (
            "File shape (kept for byte-identical export)",
            {"classes": ("collapse",), "fields": ("key_order", "int_keys", "extra", "updated_at")},
        ),
    )
    inlines = [TimelineEventInline]
    actions = ["duplicate", "export_json", "start_run"]

    @admin.display(boolean=True, description="no-op")
    def noop(self, scenario: Scenario) -> bool:
        return scenario.is_noop

    def get_urls(self):
        view = self.admin_site.admin_view
        return [
            path("<int:pk>/dry-run/", view(self.dry_run_view), name="scenarios_scenario_dry_run"),
            path("<int:pk>/export/", view(self.export_view), name="scenarios_scenario_export"),
            path(
                "<int:pk>/start-run/",
                view(self.start_run_view),
                name="scenarios_scenario_start_run",
            ),
            *super().get_urls(),
        ]

    # --- the files, imported whenever the admin reads --------------------------------------------

    def _import_files(self, request) -> None:
        report = sync_from_files()
        changed = len(report.imported) + len(report.replaced) + len(report.removed)
        if changed:
            self.message_user(
                request,
                f"scenario folder imported: {len(report.imported)} new, "
                f"{len(report.replaced)} changed on disk, {len(report.removed)} removed",
            )
        for problem in report.problems:
            self.message_user(request, problem, messages.WARNING)
        for problem in scenario_problems():
            if problem.duplicate_of:  # a file failing validation is among report.problems
                self.message_user(request, problem.detail, messages.WARNING)

    def changelist_view(self, request, extra_context=None):
        if request.method == "GET":
            self._import_files(request)
        return super().changelist_view(request, extra_context)

    def add_view(self, request, form_url="", extra_context=None):
        extra_context = {**(extra_context or {}), "reference": _reference(None)}
        return super().add_view(request, form_url, extra_context)

    # --- change form --------------------------------------------------------------------------

    def change_view(self, request, object_id, form_url="", extra_context=None):
        extra_context = extra_context or {}
        if request.method == "GET":
            # Show the file's current version; a POST must not (see ScenarioForm.clean).
            self._import_files(request)
        scenario = self.get_object(request, object_id)
        if scenario is not None:
            events = timeline_of(scenario)
            extra_context["timeline_chart"] = timeline_svg(scenario, events)
            extra_context["dry_run_url"] = reverse(
                "admin:scenarios_scenario_dry_run", args=[scenario.pk]
            )
            extra_context["export_url"] = reverse(
                "admin:scenarios_scenario_export", args=[scenario.pk]
            )
            extra_context["start_run_url"] = reverse(
                "admin:scenarios_scenario_start_run", args=[scenario.pk]
            )
            extra_context["reference"] = _reference(scenario.environment)
        return super().change_view(request, object_id, form_url, extra_context)

    def response_change(self, request, obj):
        if "_dryrun" in request.POST:
            return HttpResponseRedirect(reverse("admin:scenarios_scenario_dry_run", args=[obj.pk]))
        return super().response_change(request, obj)

    def save_related(self, request, form, formsets, change):
        super().save_related(request, form, formsets, change)
        scenario = form.instance
        # Keep positions in time order, as the file format requires (sorted by time).
        for position, event in enumerate(scenario.timeline.order_by("time", "position", "id")):
            if event.position != position:
                TimelineEvent.objects.filter(pk=event.pk).update(position=position)
        try:
            parsed_scenario(scenario)
        except ScenarioError as error:
            messages.warning(request, f"Saved, but the scenario file would not load: {error}")
        try:
            write_through(scenario)  # the file is what the API and the harness run
        except ScenarioFileError as error:
            messages.error(request, f"Saved in the admin only: {error}")
            return
        previous = form.initial.get("path")
        if change and previous and previous != scenario.path:
            delete_file(Scenario(path=previous))  # moved: the old file must not come back

    def delete_model(self, request, obj):
        delete_file(obj)
        super().delete_model(request, obj)

    def delete_queryset(self, request, queryset):
        for scenario in queryset:
            delete_file(scenario)
        super().delete_queryset(request, queryset)

    # --- views ---------------------------------------------------------------------------------

    def dry_run_view(self, request, pk: int):
        scenario = get_object_or_404(Scenario, pk=pk)
        if not self.has_view_permission(request, scenario):
            from django.core.exceptions import PermissionDenied

            raise PermissionDenied
        events = timeline_of(scenario)
        result = dry_run(scenario, events)
        baseline_names = sorted({name for step in result.steps for name in step.baselines})
        context = {
            **self.admin_site.each_context(request),
            "title": f"Dry run · {scenario.scenario_id}",
            "opts": self.model._meta,
            "original": scenario,
            "scenario": scenario,
            "result": result,
            "chart": timeline_svg(scenario, events, result),
            "baseline_names": baseline_names,
            "rows": [
                (step, [step.baselines.get(n, "") for n in baseline_names]) for step in result.steps
            ],
        }
        return TemplateResponse(request, "admin/scenarios/scenario/dry_run.html", context)

    def export_view(self, request, pk: int):
        scenario = get_object_or_404(Scenario, pk=pk)
        return _download(scenario)

    def start_run_view(self, request, pk: int):
        scenario = get_object_or_404(Scenario, pk=pk)
        if request.method != "POST":
            return HttpResponseRedirect(reverse("admin:scenarios_scenario_change", args=[pk]))
        return self._start(request, scenario)

    def _start(self, request, scenario: Scenario):
        try:
            run = lifecycle.create_run(run_spec(scenario))
        except (ScenarioError, lifecycle.LifecycleError, UnknownEnvironment) as error:
            self.message_user(request, f"cannot start a run: {error}", messages.ERROR)
            return HttpResponseRedirect(
                reverse("admin:scenarios_scenario_change", args=[scenario.pk])
            )
        return HttpResponseRedirect(task_path(run))

    # --- actions -------------------------------------------------------------------------------

    @admin.action(description="Duplicate the selected scenarios")
    def duplicate(self, request, queryset):
        for scenario in queryset:
            events = timeline_of(scenario)
            copy = Scenario.objects.get(pk=scenario.pk)
            copy.pk = None
            base = scenario.path.removesuffix(".json")
            n = 1
            while Scenario.objects.filter(path=f"{base}-copy{'' if n == 1 else n}.json").exists():
                n += 1
            suffix = "-copy" if n == 1 else f"-copy{n}"
            copy.path = f"{base}{suffix}.json"
            copy.scenario_id = f"{scenario.scenario_id}{suffix}"
            copy.original_text = copy.original_canonical_sha256 = ""
            copy.save()
            for event in events:
                event.pk = None
                event.scenario = copy
            TimelineEvent.objects.bulk_create(events)
            try:
                write_through(copy)
            except ScenarioFileError as error:
                self.message_user(request, str(error), messages.ERROR)
            self.message_user(request, f"duplicated {scenario.path} as {copy.path}")

    @admin.action(description="Export as JSON (download)")
    def export_json(self, request, queryset):
        scenarios = list(queryset)
        if len(scenarios) == 1:
            return _download(scenarios[0])
        buffer = io.BytesIO()
        with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
            for scenario in scenarios:
                archive.writestr(scenario.path, scenario_text(scenario))
        response = HttpResponse(buffer.getvalue(), content_type="application/zip")
        response["Content-Disposition"] = 'attachment; filename="scenarios.zip"'
        return response

    @admin.action(description="Start a run and open its task URL")
    def start_run(self, request, queryset):
        scenarios = list(queryset)
        if len(scenarios) != 1:
            self.message_user(
                request, "select exactly one scenario to start a run", messages.WARNING
            )
            return None
        return self._start(request, scenarios[0])


def _reference(current: str | None) -> list[dict]:
    """Every environment's event types and evaluation tables, the current one first."""
    names = sorted(environment.name for environment in all_environments())
    if current in names:
        names.remove(current)
        names.insert(0, current)
    return [
        {
            "environment": name,
            "open": name == current,
            "event_types": event_types(name),
            "tables": evaluation_tables(name),
        }
        for name in names
    ]


def _download(scenario: Scenario) -> HttpResponse:
    response = HttpResponse(scenario_text(scenario), content_type="application/json; charset=utf-8")
    filename = scenario.path.rsplit("/", 1)[-1]
    response["Content-Disposition"] = f'attachment; filename="{filename}"'
    return response
