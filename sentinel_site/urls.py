from django.contrib import admin
from django.templatetags.static import static
from django.urls import include, path
from django.views.generic import RedirectView

from apps.control.urls import api_urlpatterns, flat_urlpatterns, run_urlpatterns
from apps.kit.views import no_such_page
from events.registry import all_environments

# The one spelling of a run's URL prefix: every run URL is reverse()d from the patterns below.
RUN_PREFIX = "r/<str:token>/"
RUN_PATHS = "/" + RUN_PREFIX.split("<", 1)[0]  # "/r/": every path under a run's prefix starts so

urlpatterns = [
    path("favicon.ico", RedirectView.as_view(url=static("site/favicon.svg"), permanent=True)),
    path("", include("apps.home.urls")),  # the home page: environments, scenarios, runs, docs
    path("admin/", admin.site.urls),
    path("api/", include(api_urlpatterns)),
    path("media/", include("apps.media.urls")),  # generated avatars, logos, pictures (no run)
    path(RUN_PREFIX, include(run_urlpatterns)),
    path(RUN_PREFIX, include("apps.kit.urls")),  # the run's home, live pages' polling
    # Each environment's pages, under its run: /r/<token>/<environment>/…, named
    # `<environment>:<page>` (its urls.py need not say its own name).
    *[
        path(f"{RUN_PREFIX}{environment.name}/", include((environment.urlconf, environment.name)))
        for environment in all_environments()
        if environment.urlconf
    ],
    # Any other address under an environment: its "does not exist" page, not Django's bare one.
    path(f"{RUN_PREFIX}<str:environment>/<path:rest>", no_such_page),
    *flat_urlpatterns,
]
