"""Pages whose only change is the clock (a relative time, the shell clock) are pushed when it
changes, over a real websocket to a real Daphne, with no timeline event firing.

The cast: a MicroMail run whose timeline holds only its t=0 preload (its newest mail arrived
`NEWEST_AGE_MIN` minutes before the start), so nothing but the clock can change its pages.
"""

from __future__ import annotations

import json
import re
import time
import urllib.request

import pytest
from django.conf import settings
from websockets.sync.client import connect

from apps.kit.live import last_live_seq
from tests import control_api
from tests.live.pushed import regions

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.e2e]

SCENARIO = settings.BASE_DIR / "scenarios" / "micromail" / "sender-absolute-passive.json"
WAIT_S = 20  # a simulated minute is 15 wall seconds at speed 4; the tests move closer to it
LIVE_DIV = re.compile(r'<div id="sentinel-live"[^>]*data-seq="(\d+)" data-due="([^"]*)"')


RECENT_MAIL = "base-23"  # our catalog dates it minutes before the start: its row reads "N min ago"


def with_recent_mail(scenario: dict) -> dict:
    """`scenario` with RECENT_MAIL among its preloaded mail (the rest is hours or days old)."""
    for event in scenario["events"]:
        if event["type"] == "preload_emails":
            event["payload"]["email_ids"] = [*event["payload"]["email_ids"], RECENT_MAIL]
    return scenario


def quiet_scenario() -> dict:
    """The scenario with nothing after its t=0 preload."""
    scenario = json.loads(SCENARIO.read_text())
    scenario["events"] = [e for e in scenario["events"] if e["time"] <= 0]
    return with_recent_mail(scenario)


def newest_preloaded_age_min(scenario: dict) -> int:
    """How many minutes before the start the scenario's newest preloaded mail arrived (its
    catalog record's `ageMinutes`): what its inbox's first row reads, "N min ago"."""
    ids = {
        email_id
        for event in scenario["events"]
        if event["type"] == "preload_emails"
        for email_id in event["payload"]["email_ids"]
    }
    catalog = settings.BASE_DIR / "fixtures" / "micromail" / "emails.jsonl"
    records = [json.loads(line) for line in catalog.read_text().splitlines()]
    return min(r["ageMinutes"] for r in records if r["id"] in ids or "*" in ids)


NEWEST_AGE_MIN = newest_preloaded_age_min(quiet_scenario())
assert NEWEST_AGE_MIN < 50, "the tests read the newest mail's age in minutes"


api = control_api.post


def open_page(base_url: str, url: str) -> tuple[int, float, str]:
    """Load the page as a browser would: the log position and due time it was rendered with."""
    with urllib.request.urlopen(f"{base_url}{url}", timeout=30) as response:
        page = response.read().decode()
    seq, due = LIVE_DIV.search(page).groups()
    clock = re.search(r'<time id="sim-clock"[^>]*>([^<]*)</time>', page).group(1)
    return int(seq), float(due), clock


def shell_clock(message: dict) -> str:
    return re.search(r">([^<]*)</time>$", regions(message)["sim-clock"]).group(1)


def test_a_running_clock_pushes_the_turning_minute_without_any_event(live_site):
    run = api(live_site, "/api/runs/", {"scenario_json": quiet_scenario(), "speed_factor": 4})
    control_api.position(run["id"], 50)  # 09:00:50: near the turn
    api(live_site, f"/api/runs/{run['id']}/start/")  # runs on from 50, 2.5 wall s to 09:01
    url = f"/r/{run['token']}/micromail/?folder=inbox"
    seq, due, clock = open_page(live_site, url)  # due: 60, or 120 on a very slow machine

    host = live_site.removeprefix("http://")
    with connect(f"ws://{host}/r/{run['token']}/live", open_timeout=WAIT_S) as socket:
        socket.send(json.dumps({"url": url, "seq": seq, "due": due}))
        message = json.loads(socket.recv(timeout=WAIT_S))

    assert message["type"] == "regions" and message["seq"] == seq
    assert shell_clock(message) != clock and message["next_change"] == due + 60
    minutes = int((due + NEWEST_AGE_MIN * 60) // 60)  # the newest preloaded mail's age
    assert f"{minutes} min ago" in regions(message)["message-list"]
    assert last_live_seq(run["id"]) == seq  # no event fired: the clock alone changed the page


def test_advancing_a_virtual_clock_past_the_minute_pushes(live_site):
    run = api(live_site, "/api/runs/", {"scenario_json": quiet_scenario(), "clock_mode": "virtual"})
    url = f"/r/{run['token']}/micromail/?folder=inbox"
    seq, due, clock = open_page(live_site, url)
    assert (due, clock[-5:]) == (60.0, "09:00")

    host = live_site.removeprefix("http://")
    with connect(f"ws://{host}/r/{run['token']}/live", open_timeout=WAIT_S) as socket:
        socket.send(json.dumps({"url": url, "seq": seq, "due": due}))
        api(live_site, f"/api/runs/{run['id']}/advance/", {"time": 30})
        with pytest.raises(TimeoutError):  # 09:00:30 reads as 09:00: nothing to push
            socket.recv(timeout=1)
        moved_at = time.monotonic()
        api(live_site, f"/api/runs/{run['id']}/advance/", {"time": 61})
        message = json.loads(socket.recv(timeout=WAIT_S))
        pushed_after = time.monotonic() - moved_at

    assert shell_clock(message).endswith("09:01") and message["next_change"] == 120.0
    assert f"{NEWEST_AGE_MIN + 1} min ago" in regions(message)["message-list"]
    assert message["seq"] == seq == last_live_seq(run["id"])
    assert pushed_after < 5
