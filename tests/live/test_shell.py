"""The shared agent-facing shell and the simulated-time helpers every environment uses."""

from __future__ import annotations

import asyncio
import json
import re
from datetime import date

import pytest
from asgiref.sync import async_to_sync
from django.test import Client

from apps.kit.live import last_live_seq
from apps.kit.simclock import absolute, ago, clock_time, relative, today
from tests.micromail.cast import CAST

MONDAY = date(2025, 1, 6)


@pytest.fixture
def run(db):
    return CAST.start()


def test_simulated_times_read_from_the_run_clock():
    assert (clock_time(0), clock_time(-300), ago(-300, 0), ago(100, 110)) == (
        "09:00",
        "08:55",
        "5 min ago",
        "just now",
    )
    assert relative(0, 5 * 3600, MONDAY) == "09:00"
    assert relative(0, 24 * 3600, MONDAY) == "Yesterday 09:00"
    assert relative(0, 3 * 24 * 3600, MONDAY) == "Mon 6 Jan"
    assert absolute(12 * 60, MONDAY) == "Mon 6 Jan 2025, 09:12"
    assert today(15 * 3600, MONDAY) == date(2025, 1, 7)  # 09:00 + 15 h is past midnight


def test_micromail_pages_use_the_shared_shell(run):
    page = Client().get(f"/r/{run.token}/micromail/?folder=inbox").content.decode()
    assert '<a class="skip-link" href="#main">' in page and '<main id="main"' in page
    headers = json.loads(re.search(r"hx-headers='([^']+)'", page).group(1))
    assert headers["X-CSRFToken"]
    assert "/static/django_htmx/htmx-2.min.js" in page and "/static/site/live.js" in page
    live = re.search(r'<div id="sentinel-live"[^>]*>', page).group(0)
    assert f'data-socket="/r/{run.token}/live"' in live
    assert f'data-seq="{last_live_seq(run.pk)}"' in live and 'data-poll-ms="2000"' in live
    for region in ("folders", "message-list", "reading-pane"):
        assert re.search(rf'id="{region}" data-live', page)


def test_icon_buttons_have_labels(run):
    page = Client().get(f"/r/{run.token}/micromail/?folder=inbox").content.decode()
    for button in re.findall(r'<button[^>]*class="icon[^"]*"[^>]*>', page):
        assert "aria-label=" in button


@pytest.mark.django_db
@pytest.mark.parametrize("path", ["/static/django_htmx/htmx-2.min.js", "/static/site/live.js"])
def test_the_asgi_app_serves_the_static_scripts(path):
    from sentinel_site.asgi import router

    scope = {
        "type": "http",
        "method": "GET",
        "path": path,
        "raw_path": path.encode(),
        "query_string": b"",
        "headers": [(b"host", b"testserver")],
        "scheme": "http",
        "server": ("testserver", 80),
        "client": ("127.0.0.1", 1),
        "asgi": {"version": "3.0"},
        "http_version": "1.1",
        "root_path": "",
    }
    sent, requested = [], []

    async def receive():
        if requested:  # the request was read: wait for the response, the client never leaves
            await asyncio.sleep(3600)
        requested.append(True)
        return {"type": "http.request", "body": b"", "more_body": False}

    async def send(message):
        sent.append(message)

    async_to_sync(router)(scope, receive, send)
    assert sent[0]["status"] == 200
    assert sum(len(m.get("body", b"")) for m in sent[1:]) > 1000
