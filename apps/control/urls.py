from django.urls import path
from drf_spectacular.views import SpectacularAPIView, SpectacularSwaggerView
from rest_framework.routers import SimpleRouter

from apps.control import agent, api, flat
from apps.control.slot import flat_endpoint

router = SimpleRouter()
router.register("runs", api.RunViewSet, basename="run")
router.register("scenarios", api.ScenarioViewSet, basename="scenario")

api_urlpatterns = [
    *router.urls,
    path("schema/", SpectacularAPIView.as_view(), name="schema"),
    # Interactive documentation; its files come from drf-spectacular-sidecar (no CDN).
    path("docs/", SpectacularSwaggerView.as_view(url_name="schema"), name="api-docs"),
]

# Upstream's protocol on the one default slot; all off with SENTINEL_FLAT_ENDPOINTS=off.
flat_urlpatterns = [
    path(route, flat_endpoint(view))
    for route, view in (
        ("status", flat.status),
        ("init", flat.init),
        ("advance", flat.advance),
        ("play", flat.play),
        ("redirect", flat.redirect),
        ("contact", agent.flat_contact),
        ("evaluate", flat.evaluate),
        ("close", flat.close),
        ("dev_init", flat.dev_init),
        ("scenarios", flat.scenarios),
        ("scenarios/<str:scenario_id>", flat.scenario_detail),
        ("data/config", flat.data_config),
        ("data/users", flat.data_users),
    )
]

run_urlpatterns = [
    path("start", agent.task_start, name="run-start"),
    path("contact", agent.run_contact, name="run-contact"),
    path("actions", agent.run_action, name="run-actions"),
    path("wait", agent.run_wait, name="run-wait"),
]
