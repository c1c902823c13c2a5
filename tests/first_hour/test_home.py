"""The home page at `/`: what the server is, where everything is, and a run to browse."""

from __future__ import annotations

import re

import httpx
import pytest

from apps.replay.records import record_verdict
from events.models import Run
from events.registry import all_environments

pytestmark = pytest.mark.django_db


def test_the_home_page_names_the_environments_and_links_everything(client, scenario_dir):
    response = client.get("/")
    assert response.status_code == 200
    html = response.content.decode()
    for environment in all_environments():
        assert f"<code>{environment.name}</code>" in html
    for link in ("/admin/", "/api/runs/", "/api/docs/", "/api/schema/", "/docs/readme/"):
        assert f'href="{link}"' in html
    scenarios = [p for p in scenario_dir.glob("*/*.json") if p.name != "dev.json"]
    assert f"{len(scenarios)} scenario files" in html


def test_browse_starts_a_run_of_the_dev_scenario(client, scenario_dir):
    assert "browse with everything preloaded" in client.get("/").content.decode()
    response = client.post("/browse/micromail/")
    run = Run.objects.get()
    assert response.status_code == 302 and response["Location"] == f"/r/{run.token}/start"
    assert run.spec["is_dev"] and run.environment == "micromail"
    assert client.post("/browse/nowhere/").status_code == 404


def test_recent_runs_show_their_verdict(client, api, scenario_dir):
    run = api.post("/api/runs/", {"scenario": "micromail-inbox-relative-passive"}, format="json")
    html = client.get("/").content.decode()
    assert "micromail-inbox-relative-passive" in html and "ready, not graded" in html
    record_verdict(Run.objects.get(pk=run.json()["id"]))
    assert ">fail</td>" in client.get("/").content.decode()


def test_the_api_documentation_is_served_without_a_cdn(client):
    html = client.get("/api/docs/").content.decode()
    assert "swagger-ui" in html and "/static/drf_spectacular_sidecar/" in html
    # Every script, stylesheet and image is ours: no address on another host (a bare "cdn"
    # could be in the page's random CSRF token, as it once was).
    sources = re.findall(r'(?:src|href)\s*[=:]\s*["\']([^"\']+)', html)
    assert sources and not [s for s in sources if re.match(r"(?:[a-z]+:)?//", s, re.I)]
    assert not re.search(r"\bcdn[.\w-]*\.(?:com|net|org|io)\b", html, re.I)
    assert client.get("/docs/readme/").status_code == 200
    assert client.get("/docs/secrets/").status_code == 404


def test_the_server_serves_the_home_page_and_swagger_ui_files(live_site):
    with httpx.Client(base_url=live_site, timeout=30) as http:
        assert http.get("/").status_code == 200
        docs = http.get("/api/docs/").text
        assets = re.findall(r'(/static/drf_spectacular_sidecar/[^"\']+)', docs)
        assert assets
        for asset in assets:
            assert http.get(asset).status_code == 200, asset
