"""The scenario admin with "Generate variants…" (apps.generate.variants).

The generator sits above both the scenario library and the harness it borrows its proofs from,
so the scenario admin cannot import it: this app registers the scenario admin again, extended
with the variants page and the link to it on the change form.
"""

from __future__ import annotations

from django.contrib import admin
from django.core.exceptions import PermissionDenied
from django.shortcuts import get_object_or_404
from django.template.response import TemplateResponse
from django.urls import path, reverse

from apps.scenarios.admin import ScenarioAdmin
from apps.scenarios.models import Scenario


class GeneratingScenarioAdmin(ScenarioAdmin):
    def get_urls(self):
        view = self.admin_site.admin_view
        variants = path(
            "<int:pk>/variants/", view(self.variants_view), name="scenarios_scenario_variants"
        )
        return [variants, *super().get_urls()]

    def change_view(self, request, object_id, form_url="", extra_context=None):
        extra_context = extra_context or {}
        if object_id and str(object_id).isdigit():
            extra_context["variants_url"] = reverse(
                "admin:scenarios_scenario_variants", args=[int(object_id)]
            )
        return super().change_view(request, object_id, form_url, extra_context)

    def variants_view(self, request, pk: int):
        """The form, then the proven variants written, listed for review."""
        scenario = get_object_or_404(Scenario, pk=pk)
        if not self.has_add_permission(request):
            raise PermissionDenied
        # The generator borrows the harness (its HTTP client among it): loaded when used, not
        # by every process that starts Django.
        from apps.generate.variants import VariantsForm, generate_variants

        form = VariantsForm(request.POST or None)
        outcome = None
        if request.method == "POST" and form.is_valid():
            outcome = generate_variants(scenario, **form.cleaned_data)
        context = {
            **self.admin_site.each_context(request),
            "title": f"Generate variants · {scenario.scenario_id}",
            "opts": self.model._meta,
            "original": scenario,
            "scenario": scenario,
            "form": form,
            "outcome": outcome,
        }
        return TemplateResponse(request, "admin/scenarios/scenario/variants.html", context)


admin.site.unregister(Scenario)
admin.site.register(Scenario, GeneratingScenarioAdmin)
