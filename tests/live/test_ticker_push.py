"""The ticker — whichever backend is configured — pushes to open pages without any request.

A real Daphne serves the test database. Embedded, its in-process ticker fires and the in-memory
layer carries the push; with SENTINEL_TICKER=celery a real Celery worker fires and Redis carries
the push from the worker process to Daphne.
"""

from __future__ import annotations

import json
import time

import pytest
from django.conf import settings
from websockets.sync.client import connect

from tests import control_api

pytestmark = pytest.mark.e2e

SCENARIO = settings.BASE_DIR / "scenarios" / "micromail" / "sender-absolute-passive.json"
FIRST_NEW = "base-36"  # the first new_email after the preload, brought forward below
WAIT_S = 30


def early_scenario() -> dict:
    """The scenario with its first new mail due at t=4 (1 s of wall time at speed 4)."""
    scenario = json.loads(SCENARIO.read_text())
    first = next(e for e in scenario["events"] if e["type"] == "new_email")
    assert first["payload"]["email_id"] == FIRST_NEW
    first["time"] = 4.0
    return scenario


api = control_api.post


@pytest.mark.django_db(transaction=True)
def test_the_ticker_pushes_new_mail_to_an_open_inbox(live_site, site_ticker):
    run = api(live_site, "/api/runs/", {"scenario_json": early_scenario(), "speed_factor": 4})
    host = live_site.removeprefix("http://")
    url = f"/r/{run['token']}/micromail/?folder=inbox"
    with connect(f"ws://{host}/r/{run['token']}/live", open_timeout=WAIT_S) as socket:
        socket.send(json.dumps({"url": url, "seq": 1}))  # seq 1 = the t=0 preload only
        first = json.loads(socket.recv(timeout=WAIT_S))  # subscribing late still catches up
        assert first["type"] == "regions" and FIRST_NEW not in first["html"]
        api(live_site, f"/api/runs/{run['id']}/start/")
        deadline = time.monotonic() + WAIT_S
        while time.monotonic() < deadline:
            message = json.loads(socket.recv(timeout=WAIT_S))
            if f"email={FIRST_NEW}" in message["html"]:
                break
        else:
            pytest.fail("the ticker's event was never pushed")
    assert message["seq"] > first["seq"]
