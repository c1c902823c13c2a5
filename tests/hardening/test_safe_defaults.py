"""The default configuration is closed to other web pages: a page on another site cannot drive
the control API through its visitor's browser (a cross-site form post created and closed runs),
and a foreign Host header (DNS rebinding) is refused before anything is read."""

from __future__ import annotations

import pytest
from asgiref.sync import async_to_sync
from channels.testing import WebsocketCommunicator
from rest_framework.test import APIClient

from apps.kit.links import live_path
from events import lifecycle
from events.models import ClockMode, Run

pytestmark = pytest.mark.django_db

EVIL = "https://evil.example"


@pytest.fixture
def api():
    return APIClient()


def test_a_cross_site_form_post_creates_no_run(api):
    response = api.post(
        "/api/runs/", {"scenario": "micromail-inbox-relative-passive"}, HTTP_ORIGIN=EVIL
    )
    assert response.status_code == 403
    assert "cross-site request refused" in response.json()["detail"]
    assert not Run.objects.exists()


def test_a_cross_site_json_post_closes_no_run(api, tally_spec):
    run = lifecycle.create_run(tally_spec(), clock_mode=ClockMode.VIRTUAL)
    response = api.post(f"/api/runs/{run.pk}/close/", {}, format="json", HTTP_ORIGIN=EVIL)
    assert response.status_code == 403
    run.refresh_from_db()
    assert run.closed_at is None


def test_the_api_answers_its_own_pages_and_clients_that_are_not_browsers(api, tally_spec):
    run = lifecycle.create_run(tally_spec(), clock_mode=ClockMode.VIRTUAL)
    own = api.post(
        f"/api/runs/{run.pk}/advance/", {"time": 5}, format="json", HTTP_ORIGIN="http://testserver"
    )
    assert own.status_code == 200
    assert api.post(f"/api/runs/{run.pk}/close/", {}, format="json").status_code == 200


def test_reading_is_not_refused_by_origin(api):
    # Reads change nothing; what protects them is the Host check below and the control token.
    assert api.get("/api/runs/", HTTP_ORIGIN=EVIL).status_code == 200


def test_the_api_takes_json_bodies_only(api, tally_spec):
    run = lifecycle.create_run(tally_spec(), clock_mode=ClockMode.VIRTUAL)
    response = api.post(f"/api/runs/{run.pk}/advance/", {"time": 5}, format="multipart")
    assert response.status_code == 415
    assert "multipart/form-data" in response.json()["detail"]


def test_a_foreign_host_name_is_refused(api):
    # A page at evil.example whose name was made to resolve to 127.0.0.1 asks with its own name.
    assert api.get("/api/runs/", HTTP_HOST="evil.example").status_code == 400
    assert api.get("/api/runs/", HTTP_HOST="127.0.0.1:8000").status_code == 200
    assert api.get("/api/runs/", HTTP_HOST="localhost").status_code == 200


@pytest.mark.django_db(transaction=True)
@pytest.mark.parametrize(
    "origin,accepted",
    [(None, True), ("http://127.0.0.1:8000", True), (EVIL, False)],
)
def test_a_live_socket_from_another_site_is_refused(tally_spec, settings, origin, accepted):
    settings.CHANNEL_LAYERS = {"default": {"BACKEND": "channels.layers.InMemoryChannelLayer"}}
    from channels.layers import channel_layers

    channel_layers.backends.clear()
    run = lifecycle.create_run(tally_spec(), clock_mode=ClockMode.LIVE)
    headers = [(b"origin", origin.encode())] if origin else []

    async def connect() -> bool:
        from sentinel_site.asgi import router

        socket = WebsocketCommunicator(router, live_path(run), headers=headers)
        connected, _ = await socket.connect(timeout=10)
        await socket.disconnect()
        return connected

    try:
        assert async_to_sync(connect)() is accepted
    finally:
        channel_layers.backends.clear()


def exposure(host: str, **env: str):
    import os
    import subprocess
    import sys

    clean = {k: v for k, v in os.environ.items() if k != "SENTINEL_CONTROL_TOKEN"}
    return subprocess.run(
        [sys.executable, "-m", "sentinel_site.exposure", host],
        env={**clean, **env},
        capture_output=True,
        text=True,
        check=True,
    )


@pytest.mark.parametrize("host", ["0.0.0.0", "192.168.1.20", "bench.example.org", "::"])
def test_a_server_listening_beyond_loopback_gets_a_control_token(host):
    started = exposure(host)
    token = started.stdout.removeprefix("export SENTINEL_CONTROL_TOKEN=").strip()
    assert len(token) >= 32
    assert f"Authorization: Bearer {token}" in started.stderr
    assert exposure(host).stdout != started.stdout  # fresh for every start


@pytest.mark.parametrize("host", ["127.0.0.1", "localhost", "::1", "[::1]", "127.0.0.2"])
def test_a_loopback_server_keeps_the_open_default(host):
    assert exposure(host).stdout == ""


def test_a_configured_token_is_kept():
    assert exposure("0.0.0.0", SENTINEL_CONTROL_TOKEN="chosen").stdout == ""


def test_the_run_list_comes_a_page_at_a_time_newest_first(api, tally_spec):
    made = [lifecycle.create_run(tally_spec(), clock_mode=ClockMode.VIRTUAL).pk for _ in range(5)]
    first = api.get("/api/runs/?limit=2")
    assert [row["id"] for row in first.json()] == made[::-1][:2]
    seen = [row["id"] for row in first.json()]
    url = first["Link"]
    while url:
        page = api.get(url.split(">")[0].strip("<"))
        seen += [row["id"] for row in page.json()]
        url = page.get("Link")
    assert seen == made[::-1]
    assert "Link" not in api.get("/api/runs/").headers  # five fit in the default page


@pytest.mark.parametrize("query", ["limit=0", "limit=abc", "limit=5000", "before=-1"])
def test_a_bad_page_request_names_the_parameter(api, query):
    response = api.get(f"/api/runs/?{query}")
    assert response.status_code == 400
    assert query.split("=")[0] in response.json()["detail"]


def test_with_a_control_token_the_home_page_lists_runs_to_admins_only(
    client, admin_client, settings, tally_spec
):
    settings.SENTINEL_CONTROL_TOKEN = "secret"
    run = lifecycle.create_run(tally_spec(), clock_mode=ClockMode.VIRTUAL)
    public = client.get("/").content.decode()
    assert 'id="runs"' not in public and "log in" in public
    assert str(settings.SENTINEL_SCENARIO_DIR) not in public  # nor where the answer key lies
    assert 'id="runs"' in admin_client.get("/").content.decode()
    settings.SENTINEL_CONTROL_TOKEN = ""
    assert f"/admin/events/run/{run.pk}/change/" in client.get("/").content.decode()


def test_a_broken_scenario_file_is_named_on_the_home_page_without_where_the_folder_lies(
    client, settings, tmp_path
):
    """The home page (which an agent's browser can open) lists the folder's problems by their
    place in it; an invalid file's message used to carry the folder's absolute path."""
    (tmp_path / "micromail").mkdir()
    (tmp_path / "micromail" / "broken.json").write_text('{"id": "x",, }')
    settings.SENTINEL_SCENARIO_DIR = tmp_path
    settings.SENTINEL_CONTROL_TOKEN = "secret"
    public = client.get("/").content.decode()
    assert "micromail/broken.json" in public and "invalid JSON at line 1" in public
    assert str(tmp_path) not in public


def test_run_creation_is_rate_limited_per_client_unless_it_holds_the_token(api, settings):
    from django.core.cache import cache

    cache.clear()  # the throttle's history: this test's alone
    settings.SENTINEL_RUN_CREATION_RATE = "2/min"
    body = {"scenario": "micromail-inbox-relative-passive"}
    assert [api.post("/api/runs/", body, format="json").status_code for _ in range(2)] == [201] * 2
    refused = api.post("/api/runs/", body, format="json")
    assert refused.status_code == 429
    assert "SENTINEL_RUN_CREATION_RATE" in refused.json()["detail"]
    other = APIClient(REMOTE_ADDR="10.1.2.3")  # another address has its own count
    assert other.post("/api/runs/", body, format="json").status_code == 201
    settings.SENTINEL_CONTROL_TOKEN = "secret"
    api.credentials(HTTP_AUTHORIZATION="Bearer secret")
    assert api.post("/api/runs/", body, format="json").status_code == 201
    cache.clear()


@pytest.fixture
def creation_rate(settings):
    """Two runs a minute per client, counted from nothing."""
    from django.core.cache import cache

    cache.clear()  # the throttle's history: this test's alone
    settings.SENTINEL_RUN_CREATION_RATE = "2/min"
    yield
    cache.clear()


RUN_BODY = {"scenario": "micromail-inbox-relative-passive"}


def test_a_forwarded_for_header_does_not_make_a_new_client(api, creation_rate):
    """The audit's bypass: DRF's identity believed X-Forwarded-For, so a client that varied it
    created runs past the 429 without end."""
    assert [api.post("/api/runs/", RUN_BODY, format="json").status_code for _ in range(2)] == [
        201
    ] * 2
    forged = [
        api.post("/api/runs/", RUN_BODY, format="json", HTTP_X_FORWARDED_FOR=f"10.0.0.{i}")
        for i in range(5)
    ]
    assert [r.status_code for r in forged] == [429] * 5
    assert Run.objects.count() == 2


def test_behind_a_trusted_proxy_each_forwarded_client_has_its_own_count(settings, creation_rate):
    settings.SENTINEL_TRUSTED_PROXIES = ("10.9.0.0/16",)
    proxy = APIClient(REMOTE_ADDR="10.9.0.1")

    def create(forwarded: str) -> int:
        return proxy.post(
            "/api/runs/", RUN_BODY, format="json", HTTP_X_FORWARDED_FOR=forwarded
        ).status_code

    assert [create("192.0.2.7") for _ in range(3)] == [201, 201, 429]
    assert create("192.0.2.8") == 201  # another client behind the proxy
    # What the client itself wrote left of the proxy's entry is not believed.
    assert create("198.51.100.1, 192.0.2.7") == 429
    # A direct client (not a trusted proxy) cannot borrow another's address.
    direct = APIClient(REMOTE_ADDR="192.0.2.99")
    statuses = [
        direct.post(
            "/api/runs/", RUN_BODY, format="json", HTTP_X_FORWARDED_FOR=f"203.0.113.{i}"
        ).status_code
        for i in range(3)
    ]
    assert statuses == [201, 201, 429]


def test_a_flat_reset_counts_against_the_same_limit(api, creation_rate, tally_spec):
    """The audit's second way round: `GET /close` then `POST /init` made runs without limit."""
    spec = tally_spec()
    init = {k: spec[k] for k in ("environment", "event_timeline_end", "events")}
    made = []
    for _ in range(3):
        api.get("/close")
        made.append(api.post("/init", init, format="json"))
    assert [r.status_code for r in made] == [200, 200, 429]
    assert "SENTINEL_RUN_CREATION_RATE" in made[2].json()["detail"]
    assert made[2].headers["Retry-After"]
    assert Run.objects.count() == 2
    # The API and the flat slot share one count per client.
    assert api.post("/api/runs/", RUN_BODY, format="json").status_code == 429


def test_trusted_proxies_are_addresses_or_networks_and_none_by_default(monkeypatch):
    from sentinel_site.config import ConfigError, env_networks

    monkeypatch.delenv("SENTINEL_TRUSTED_PROXIES", raising=False)
    assert env_networks("SENTINEL_TRUSTED_PROXIES") == ()
    monkeypatch.setenv("SENTINEL_TRUSTED_PROXIES", "10.0.0.5, 10.1.0.0/16,::1")
    assert env_networks("SENTINEL_TRUSTED_PROXIES") == ("10.0.0.5", "10.1.0.0/16", "::1")
    monkeypatch.setenv("SENTINEL_TRUSTED_PROXIES", "10.0.0.5,proxy.example")
    with pytest.raises(ConfigError, match=r"'proxy\.example' is not an IP address"):
        env_networks("SENTINEL_TRUSTED_PROXIES")


# --- the flat protocol's GETs, from another site's page ----------------------------------------

# What Chromium sends with `<img src="http://127.0.0.1:8000/close">` on another site's page.
IMAGE_FROM_ANOTHER_SITE = {
    "HTTP_SEC_FETCH_SITE": "cross-site",
    "HTTP_SEC_FETCH_MODE": "no-cors",
    "HTTP_SEC_FETCH_DEST": "image",
    "HTTP_REFERER": f"{EVIL}/",
}


@pytest.fixture
def default_run(api, tally_spec) -> Run:
    """The flat slot's run, as the original's scripts make it (no token: the default)."""
    spec = tally_spec()
    init = {k: spec[k] for k in ("environment", "event_timeline_end", "events")}
    assert api.post("/init", init, format="json").status_code == 200
    return Run.objects.get(is_default_slot=True, closed_at__isnull=True)


@pytest.mark.parametrize("path", ["/advance?time=300", "/play", "/redirect", "/contact", "/close"])
def test_an_image_on_another_site_changes_nothing_on_the_default_slot(api, default_run, path):
    """The audit's break: cross-site GETs advanced and closed the default run."""
    logged = default_run.events.count()
    refused = api.get(path, **IMAGE_FROM_ANOTHER_SITE)
    assert refused.status_code == 403
    detail = refused.json()["detail"]
    assert "cross-site request refused (Sec-Fetch-Site: cross-site)" in detail
    assert "\n" not in detail
    default_run.refresh_from_db()
    assert default_run.closed_at is None and default_run.status == "ready"
    assert default_run.events.count() == logged


@pytest.mark.parametrize("site", ["same-site", "cross-site"])
def test_a_form_on_another_site_cannot_contact_or_reset_the_slot(api, default_run, site):
    """A form post: a simple request, no preflight; the contact page takes forms."""
    headers = {"HTTP_ORIGIN": EVIL, "HTTP_SEC_FETCH_SITE": site, "HTTP_SEC_FETCH_MODE": "navigate"}
    assert api.post("/contact", {"message": "done"}, **headers).status_code == 403
    assert api.post("/evaluate", **headers).status_code == 403
    assert api.post("/dev_init?environment=tally", **headers).status_code == 403
    default_run.refresh_from_db()
    assert default_run.closed_at is None and default_run.status == "ready"


def test_a_script_on_another_site_without_fetch_metadata_is_refused_by_its_origin(api, default_run):
    """A browser that sends no Sec-Fetch-Site (plain HTTP beyond loopback) still sends Origin
    with a script's request."""
    assert api.get("/close", HTTP_ORIGIN=EVIL).status_code == 403
    default_run.refresh_from_db()
    assert default_run.closed_at is None


def test_the_original_scripts_and_our_own_pages_still_drive_the_slot(api, default_run):
    # Plain HTTP clients (requests, httpx, curl): no browser headers at all.
    assert api.get("/advance?time=12").status_code == 200
    # Our own pages, and the person at the browser typing the address.
    own = {"HTTP_SEC_FETCH_SITE": "same-origin", "HTTP_ORIGIN": "http://testserver"}
    assert api.get("/advance?time=20", **own).status_code == 200
    typed = {"HTTP_SEC_FETCH_SITE": "none", "HTTP_SEC_FETCH_MODE": "navigate"}
    assert api.get("/contact", **typed).status_code == 200
    assert api.post("/contact", {"message": "done"}, **own).status_code == 200
    # Reading is not judged: another site's page learns nothing from an image's answer.
    assert api.get("/status", **IMAGE_FROM_ANOTHER_SITE).status_code == 200
    assert api.get("/close").json()["status"] == "preinit"
    default_run.refresh_from_db()
    assert default_run.closed_at is not None


def test_an_origin_the_operator_trusts_may_drive_the_slot(api, default_run, settings):
    settings.CSRF_TRUSTED_ORIGINS = ["https://bench.example.org"]
    trusted = {"HTTP_ORIGIN": "https://bench.example.org", "HTTP_SEC_FETCH_SITE": "cross-site"}
    assert api.get("/play", **trusted).status_code == 200


def test_the_control_api_refuses_another_sites_page_by_fetch_metadata_too(api, tally_spec):
    run = lifecycle.create_run(tally_spec(), clock_mode=ClockMode.VIRTUAL)
    response = api.post(
        f"/api/runs/{run.pk}/close/", {}, format="json", HTTP_SEC_FETCH_SITE="same-site"
    )
    assert response.status_code == 403
    assert "Sec-Fetch-Site: same-site" in response.json()["detail"]
    run.refresh_from_db()
    assert run.closed_at is None
