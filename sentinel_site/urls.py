from django.contrib import admin
from django.urls import include, path

from apps.control.urls import api_urlpatterns, flat_urlpatterns, run_urlpatterns
from events.registry import all_environments

urlpatterns = [
    path("admin/", admin.site.urls),
    path("api/", include(api_urlpatterns)),
    path("r/<str:token>/", include(run_urlpatterns)),
    path("r/<str:token>/", include("apps.agent_site.urls")),  # live pages: the polling fallback
    # Each environment's pages, under its run: /r/<token>/<environment>/…
    *[
        path(f"r/<str:token>/{environment.name}/", include(environment.urlconf))
        for environment in all_environments()
        if environment.urlconf
    ],
    *flat_urlpatterns,
]
