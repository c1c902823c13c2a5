"""A real browser on a real server: an open page follows a fast-forward skip at once.

The cast: a MicroMail inbox at speed 1 on a fast_forward run (the paper's sender scenario: its
newest preloaded mail `NEWEST_AGE_MIN` minutes old at the start, new mail at 41 s and 98 s). The agent's skip of 150 simulated
seconds is posted while the page is open; without a reload the page then shows the clock two
minutes on, both new emails, and relative times that moved with the jump (no stale age).
"""

from __future__ import annotations

import pytest
from django.conf import settings

from tests import control_api
from tests.live.test_clock_push import NEWEST_AGE_MIN, with_recent_mail

pytestmark = [pytest.mark.browser, pytest.mark.django_db(transaction=True)]

SCENARIO = settings.BASE_DIR / "scenarios" / "micromail" / "sender-absolute-passive.json"
PUSH_CEILING_MS = 30_000  # a push takes milliseconds; a loaded machine gets a generous ceiling
SHOWN = """() => ({
    clock: document.getElementById("sim-clock").innerText,
    rows: document.querySelectorAll("#message-list time.when").length,
    ago: Array.from(document.querySelectorAll("#message-list time.when")).map((t) => t.innerText),
    seq: Number(document.getElementById("sentinel-live").dataset.seq),
    due: Number(document.getElementById("sentinel-live").dataset.due),
})"""


def test_an_open_page_shows_the_new_time_and_the_new_mail_after_a_skip(live_site, browser):
    import json

    scenario = with_recent_mail(json.loads(SCENARIO.read_text()))
    # Its first two new mails at 41.27 and 97.83 s, the rest after the skip: what this test
    # looks at does not move when the scenario file is re-timed.
    mails = [event for event in scenario["events"] if event["type"] == "new_email"]
    for event, time in zip(mails, [41.27, 97.83, *range(200, 200 + len(mails))], strict=False):
        event["time"] = float(time)
    scenario["condition_at"] = 41.27
    run = control_api.post(
        live_site, "/api/runs/", {"scenario_json": scenario, "clock_mode": "fast_forward"}
    )
    page = browser.new_page()
    page.goto(run["task_url"])  # starts the clock, lands on the inbox
    page.wait_for_selector("#message-list time.when")
    page.evaluate("window.loadedOnce = true")  # gone if the page reloads
    before = page.evaluate(SHOWN)
    assert before["clock"].endswith("09:00")
    newest, moved = f"{NEWEST_AGE_MIN} min ago", f"{NEWEST_AGE_MIN + 2} min ago"
    assert newest in before["ago"]  # the newest preloaded mail

    answer = control_api.post(live_site, run["wait_url"].removeprefix(live_site), {"seconds": 150})
    assert [fired["at"] for fired in answer["fired"]] == [41.27, 97.83]
    assert answer["sim_time"] == pytest.approx(answer["from"] + 150)

    # What a fast-forward agent waits for: the page has the log position the skip answered and
    # a clock window that starts after the new moment.
    page.wait_for_function(
        """([seq, now]) => {
            const live = document.getElementById("sentinel-live").dataset;
            return Number(live.seq) >= seq && live.due !== "" && Number(live.due) > now &&
                document.getElementById("sim-clock").innerText.endsWith("09:02");
        }""",
        arg=[answer["seq"], answer["sim_time"]],
        timeout=PUSH_CEILING_MS,
    )
    after = page.evaluate(SHOWN)
    assert after["rows"] == before["rows"] + 2
    assert after["ago"][:2] == ["just now", "1 min ago"] or after["ago"][:2] == [
        "just now",
        "2 min ago",
    ]  # cc-05 (98 s) and base-36 (41 s), seen at 152 s
    assert moved in after["ago"] and newest not in after["ago"]
    assert page.evaluate("window.loadedOnce") is True, "the page reloaded"
