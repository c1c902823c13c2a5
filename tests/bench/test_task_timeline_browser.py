"""The task timeline of a real harness run: `bench run` with the `wait_for` reference agent (a
real subprocess driving Debian's Chromium through the embedded server, its model the scripted
server), then the page in the admin, in Chromium.

The story: the self user waits for Kevin Lee's email. Four other mails arrive first, so the
agent's wait_for asks its model about them, each "no" doubling the wait before the next
question; Kevin's mail (the trigger, at 120 simulated seconds) arrives while wait_for is between
two questions. The next question shows the model his mail's diff block, the model says yes, the
agent reports. On the timeline, in simulated seconds: the agent's first model call, the
trigger, then the question that showed it, then the contact.

The run is on the fast-forward clock: wait_for skips between its looks instead of sleeping, and
looks and asks at the simulated moments a live watcher would (tests/browser_agent/
test_wait_for_fast_forward.py), so the timeline is the live one's, in seconds of wall time
instead of a minute and a half.
"""

from __future__ import annotations

import io
import json
import re
from pathlib import Path

import pytest
import yaml
from django.contrib.auth import get_user_model
from django.core.management import call_command

from apps.browser_agent.scripted_model import parse_script, scripted_model_server
from tests.bench.conftest import shorten
from tests.browser_story import TIMEOUT_MS

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.browser]

MODEL = "scripted-1"
SUBJECT = "Expense reports: submission window closes early"  # Kevin Lee's mail, the trigger
TRIGGER_AT = 120.0
SPEED = 2
SCRIPT = {
    "model": MODEL,
    "agent": [
        {"call": "wait_for", "arguments": {"condition": "an email from Kevin Lee", "timeout": 300}},
        {"when_last_result": "met: true", "call": "contact",
         "arguments": {"message": "Kevin Lee has written to you."}},
        {"otherwise": True, "call": "terminate", "arguments": {"reason": "he never wrote"}},
    ],
    "judge": {"yes_when_any": [SUBJECT]},
}  # fmt: skip
ADMIN, PASSWORD = "grace", "correct horse battery staple"


@pytest.fixture
def graded_task(tmp_path, settings, live_site):
    """The harness run, graded, and an admin who may log in (all before the browser starts:
    Playwright's sync API runs an event loop in this thread, where the ORM refuses to work)."""
    root = tmp_path / "scenarios"
    (root / "micromail").mkdir(parents=True)
    data = shorten(
        "sender-absolute-passive", "timeline-kevin", "", condition_at=TRIGGER_AT, kill_at=300.0,
        end=320.0,
    )  # fmt: skip
    data["prompt"] = data["prompt"].removesuffix("\n[[script: ]]")
    (root / "micromail" / "timeline-kevin.json").write_text(json.dumps(data))
    settings.SENTINEL_SCENARIO_DIR = root
    results, config = tmp_path / "results", tmp_path / "eval_config.yaml"
    with scripted_model_server(parse_script(SCRIPT)) as model:
        config.write_text(
            yaml.safe_dump(
                {
                    "speed_factor": SPEED,
                    "clock": "fast_forward",
                    "parallel": 1,
                    "grace": 5,
                    "agent": {"kind": "wait_for", "model": MODEL, "base_url": model.base_url},
                }
            )
        )
        common = ("--config", str(config), "--results-dir", str(results))
        out = io.StringIO()
        call_command("bench", "run", "waiting", *common, stdout=out)
        assert "ran=1 passed=1" in out.getvalue(), out.getvalue()
    report = tmp_path / "report.html"
    out = io.StringIO()
    call_command("bench", "grade", "waiting", "--html", str(report), *common, stdout=out)
    folder = results / "waiting" / "micromail" / "timeline-kevin"
    result = json.loads((folder / "results.json").read_text())
    get_user_model().objects.create_superuser(ADMIN, "grace@example.test", PASSWORD)
    return live_site, result, report, out.getvalue(), folder


def log_in(page, site: str) -> None:
    page.goto(f"{site}/admin/login/")
    page.fill("#id_username", ADMIN)
    page.fill("#id_password", PASSWORD)
    page.click("input[type=submit]")


def test_the_timeline_puts_the_trigger_between_the_models_questions(graded_task, browser, tmp_path):
    site, result, report, graded, folder = graded_task
    path = f"/admin/events/run/{result['run']}/task/"
    # bench grade prints the task's timeline, and the report's row links to it.
    assert re.search(rf"timeline-kevin\s+http://\S+{re.escape(path)}", graded), graded
    assert f'class="timeline" href="http://127.0.0.1:8000{path}"' in report.read_text()

    page = browser.new_page(viewport={"width": 1280, "height": 800})
    page.set_default_timeout(TIMEOUT_MS)
    log_in(page, site)
    page.goto(site + path)
    page.screenshot(path=str(tmp_path / "timeline.png"), full_page=False)
    print("timeline screenshot:", tmp_path / "timeline.png")

    verdict = page.locator("#tl-verdict").inner_text()
    assert "pass" in verdict and "eval_sql returned" in verdict

    rows = page.locator("#tl-list > li")
    kinds = rows.evaluate_all("items => items.map((li) => li.className)")
    moments = [float(x) for x in rows.evaluate_all("items => items.map((li) => li.dataset.at)")]
    assert moments == sorted(moments)
    trigger = kinds.index("kind-trigger")
    assert moments[trigger] == TRIGGER_AT
    checks = [n for n, kind in enumerate(kinds) if kind == "kind-check"]
    before = [n for n in checks if n < trigger]
    after = [n for n in checks if n > trigger]
    # wait_for asked about the other mails before Kevin's arrived, and next after it: the
    # trigger came while it was between two questions.
    assert before and after
    model_calls = [n for n, kind in enumerate(kinds) if kind == "kind-model"]
    contact = kinds.index("kind-contact")
    assert model_calls[0] < before[0] < trigger < after[0] < model_calls[-1] < contact

    # The question after the trigger showed the model Kevin's mail; those before it did not.
    shown = rows.nth(after[0])
    shown.locator("summary").click()
    blocks = shown.locator("pre.block").all_inner_texts()
    assert any(SUBJECT in block for block in blocks)
    assert "→ met" in shown.locator("summary").inner_text()
    earlier = rows.nth(before[-1])
    earlier.locator("summary").click()
    assert not any(SUBJECT in block for block in earlier.locator("pre.block").all_inner_texts())

    # On the axis, in simulated seconds: first question, trigger, the question after, contact.
    def x(selector: str, index: int = 0) -> float:
        return page.locator(f"#tl-axis a.mark.{selector}").nth(index).bounding_box()["x"]

    assert x("kind-check") < x("kind-trigger") < x("kind-check", len(before)) < x("kind-contact")

    # A step expands to its screenshot (served from the agent's files in the task's folder).
    step = rows.nth(model_calls[0])
    step.locator("summary").click()
    shot = step.locator("img.screenshot")
    # decode() waits for the (lazily loaded) picture and fails if it cannot be loaded
    assert shot.evaluate("img => img.decode().then(() => img.naturalWidth)") > 0

    # "The site at this moment" opens the run's page as it was then, read-only.
    with page.expect_navigation():
        shown.locator("a.site-at").click()
    assert page.locator("#time-travel-banner").is_visible()
    assert SUBJECT in page.locator("body").inner_text()
    assert Path(folder / "agent" / "transcript.jsonl").is_file()
