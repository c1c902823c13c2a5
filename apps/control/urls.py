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

# Upstream's protocol on the one default slot; all off with SENTINEL_FLAT_ENDPOINTS=off. Those
# that change the slot's run (GETs among them) refuse another site's page (slot.flat_endpoint).
flat_urlpatterns = [
    path(route, flat_endpoint(view, changes_state=changes_state))
    for route, view, changes_state in (
        ("status", flat.status, False),
        ("init", flat.init, True),
        ("advance", flat.advance, True),
        ("play", flat.play, True),
        ("redirect", flat.redirect, True),  # starts the clock
        ("contact", agent.flat_contact, True),  # completes the run, GET or POST
        ("evaluate", flat.evaluate, True),  # completes the run
        ("close", flat.close, True),
        ("dev_init", flat.dev_init, True),
        ("scenarios", flat.scenarios, False),
        ("scenarios/<str:scenario_id>", flat.scenario_detail, False),
        ("data/config", flat.data_config, False),
        ("data/users", flat.data_users, False),
    )
]

run_urlpatterns = [
    path("start", agent.task_start, name="run-start"),
    path("contact", agent.run_contact, name="run-contact"),
    path("actions", agent.run_action, name="run-actions"),
    path("wait", agent.run_wait, name="run-wait"),
]
