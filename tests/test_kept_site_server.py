"""The site server `live_site` keeps between tests: it forgets what earlier tests left in its
memory, only a test server can be told to, and a test that starts it otherwise gets its own."""

from __future__ import annotations

import pytest
from django.contrib.contenttypes.models import ContentType

from apps.kit import screen_cache
from events import models, projection, scheduler
from events.models import Run
from tests.micromail.cast import CAST
from tests.server_urls import FORGET_PATH


def remembered(run: Run) -> dict[str, bool]:
    """Which per-process memories hold something about `run` (or any content type)."""
    return {
        "folded state": projection._cache.get((run.pk, run.catalog_hash)) is not None,
        "screens": screen_cache.cache_info() != (0, 0),
        "spec": models._spec_cache.get((run.pk, run.token)) is not None,
        "timeline hint": (run.pk, run.token) in scheduler._next_unfired,
        "content types": bool(ContentType.objects._cache),
    }


@pytest.mark.django_db
@pytest.mark.urls("tests.server_urls")
def test_the_forget_url_empties_every_memory_of_earlier_runs(client):
    run = CAST.start()
    assert client.get(f"/r/{run.token}/micromail/?folder=inbox").status_code == 200
    ContentType.objects.get_for_model(Run)
    Run.objects.defer("scenario").get(pk=run.pk).spec  # noqa: B018 - cached on read
    scheduler._remember_next_unfired(run, 1)
    assert all(remembered(run).values()), remembered(run)

    assert client.post(f"/{FORGET_PATH}").status_code == 204
    assert not any(remembered(run).values()), remembered(run)


@pytest.mark.django_db
def test_only_a_server_the_suite_keeps_can_be_told_to_forget(client):
    assert client.post(f"/{FORGET_PATH}").status_code == 404


@pytest.mark.e2e
def test_a_test_that_starts_the_server_otherwise_gets_its_own(
    live_site, kept_site_server, settings, tmp_path
):
    assert kept_site_server.serving() == live_site  # started the same way: the same server
    settings.SENTINEL_SCENARIO_DIR = tmp_path  # as own_scenarios does
    assert kept_site_server.serving() != live_site
