"""A real browser on a real server: an open inbox keeps its times current with no event firing.

The run's timeline holds only its t=0 preload (its newest mail arrived `NEWEST_AGE_MIN` minutes
before the start), so
the clock alone changes the page: the shell's simulated clock and each row's "N min ago". At
speed 4 a simulated minute is 15 wall seconds; the clock is first moved by hand to 09:00:48 and
started there, so the minute turns 3 wall seconds after the start. Over the websocket the server
pushes when the minute turns; without one, the page polls with the due time it was given.
"""

from __future__ import annotations

import json
import urllib.request

import pytest

from tests import control_api
from tests.live.test_clock_push import NEWEST_AGE_MIN, api, quiet_scenario

pytestmark = [pytest.mark.browser, pytest.mark.django_db(transaction=True)]

STARTS_AT = 48.0
# 3 s to the first turn (15 s to the next), plus a render: a ceiling for a loaded machine.
TURN_CEILING_MS = 45_000
SHOWN = """() => ({
    clock: document.getElementById("sim-clock").innerText,
    datetime: document.getElementById("sim-clock").getAttribute("datetime"),
    ago: document.querySelector("#message-list time.when").innerText,
})"""


def scenario_events(base_url: str, run_id: int) -> list[dict]:
    """The run's log as the control API gives it (the browser's loop forbids ORM calls here)."""
    with urllib.request.urlopen(f"{base_url}/api/runs/{run_id}/events/", timeout=30) as response:
        return [e for e in json.load(response) if e["kind"] == "scenario"]


@pytest.mark.parametrize("transport", ["websocket", "polling"])
def test_the_shell_clock_and_relative_times_advance_by_themselves(live_site, browser, transport):
    run = api(live_site, "/api/runs/", {"scenario_json": quiet_scenario(), "speed_factor": 4})
    control_api.position(run["id"], STARTS_AT)
    api(live_site, f"/api/runs/{run['id']}/start/")
    context = browser.new_context(viewport={"width": 1100, "height": 420})
    if transport == "polling":
        context.add_init_script("window.WebSocket = undefined;")
    page = context.new_page()
    page.goto(f"{live_site}/r/{run['token']}/micromail/?folder=inbox")
    page.evaluate("window.loadedOnce = true")  # gone if the page reloads
    # Read in one go (atomic against a turn in between). A loaded machine may render the page
    # after the first turn: then the next turn, 15 wall s later, is the one watched.
    shown = page.evaluate(SHOWN)
    minute = int(shown["clock"].rsplit(":", 1)[1])
    ago = int(shown["ago"].split()[0])
    assert shown["clock"].endswith(f"09:{minute:02d}") and minute in (0, 1)
    assert shown["ago"] == f"{ago} min ago" and ago == NEWEST_AGE_MIN + minute

    page.wait_for_function(
        """([clock, ago]) => document.getElementById("sim-clock").innerText !== clock &&
             document.querySelector("#message-list time.when").innerText !== ago""",
        arg=[shown["clock"], shown["ago"]],
        timeout=TURN_CEILING_MS,
    )
    turned = page.evaluate(SHOWN)
    assert turned["clock"].endswith(f"09:{minute + 1:02d}")
    assert turned["ago"] == f"{ago + 1} min ago"
    assert turned["datetime"].endswith(f"T09:{minute + 1:02d}")
    assert page.evaluate("window.loadedOnce") is True, "the page reloaded"
    assert [e["type"] for e in scenario_events(live_site, run["id"])] == ["preload_emails"]
