from django.urls import path
from drf_spectacular.views import SpectacularAPIView
from rest_framework.routers import SimpleRouter

from apps.control import agent, api, flat

router = SimpleRouter()
router.register("runs", api.RunViewSet, basename="run")
router.register("scenarios", api.ScenarioViewSet, basename="scenario")

api_urlpatterns = [
    *router.urls,
    path("schema/", SpectacularAPIView.as_view(), name="schema"),
]

flat_urlpatterns = [
    path("status", flat.status),
    path("init", flat.init),
    path("advance", flat.advance),
    path("play", flat.play),
    path("redirect", flat.redirect),
    path("contact", agent.flat_contact),
    path("evaluate", flat.evaluate),
    path("close", flat.close),
    path("dev_init", flat.dev_init),
    path("scenarios", flat.scenarios),
    path("scenarios/<str:scenario_id>", flat.scenario_detail),
    path("data/config", flat.data_config),
    path("data/users", flat.data_users),
]

run_urlpatterns = [
    path("start", agent.task_start, name="run-start"),
    path("contact", agent.run_contact, name="run-contact"),
    path("actions", agent.run_action, name="run-actions"),
]
