"""An author in a real browser: reads the reference panel, creates a scenario, sees a broken
eval_sql refused on save, fixes it, starts a run from the change page, and the API's runs of
the scenario play the timeline as edited."""

from __future__ import annotations

import shutil

import httpx
import pytest
from django.contrib.auth import get_user_model

from sentinel_site.site_server import site_server
from tests.browser_story import admin_page
from tests.conftest import OUR_SCENARIOS

pytestmark = [pytest.mark.browser, pytest.mark.django_db(transaction=True)]

AUTHOR, PASSWORD = "grace", "correct horse battery staple"
SCENARIO_ID = "micromail-first-hour"


@pytest.fixture
def author_site(transactional_db, tmp_path, settings):
    """A server on the test database whose scenario folder is a fresh copy of ours."""
    get_user_model().objects.create_superuser(AUTHOR, "grace@example.test", PASSWORD)
    root = tmp_path / "scenarios"
    shutil.copytree(OUR_SCENARIOS / "micromail", root / "micromail")
    settings.SENTINEL_SCENARIO_DIR = root  # the server started below shares it
    with site_server(log_path=settings.BASE_DIR / "var" / "live-site.log") as base_url:
        yield base_url, root


def test_an_author_creates_a_scenario_and_runs_it(author_site, browser):
    base_url, root = author_site
    page = admin_page(browser, base_url, AUTHOR, PASSWORD)

    page.goto(f"{base_url}/admin/scenarios/scenario/add/")
    reference = page.locator('#scenario-reference details[data-environment="micromail"]')
    reference.locator("summary").click()
    event_row = reference.locator(".reference-event-types tr", has_text="new_email")
    assert "email_id" in event_row.inner_text()
    emails_row = reference.locator(".reference-tables tr", has_text="email_states")
    assert "isRead" in emails_row.inner_text()

    page.fill("#id_scenario_id", SCENARIO_ID)
    page.fill("#id_environment", "micromail")
    page.fill("#id_path", "micromail/first-hour.json")
    page.fill("#id_prompt", "Tell me when the vendor's quote arrives.")
    page.fill("#id_start_page", "HOST_ADDRESS/micromail")
    page.fill("#id_condition_at", "12")
    page.fill("#id_event_timeline_end", "60")
    page.fill("#id_kill_at", "60")
    page.fill("#id_taxonomy", '{"monitoring_approach": "passive", "milestone_type": "absolute"}')
    page.fill("#id_eval_sql", "SELECT COUNT(*) FROM email_states WHERE is_read = 0")
    page.click(".add-row a")
    page.fill("input[name='timeline-0-time']", "12")
    page.fill("input[name='timeline-0-type']", "new_email")
    page.fill("textarea[name='timeline-0-payload']", '{"email_id": "base-04"}')
    page.click("input[name='_continue']")

    error = page.locator(".field-eval_sql .errorlist")
    assert "no such column: is_read" in error.inner_text()
    assert not (root / "micromail" / "first-hour.json").exists()

    page.fill("#id_eval_sql", "SELECT COUNT(*) FROM email_states WHERE isRead = 0")
    page.click("input[name='_continue']")
    page.wait_for_selector("#start-run")
    assert (root / "micromail" / "first-hour.json").is_file()

    with page.expect_popup() as popup:
        page.click("#start-run")
    run_page = popup.value
    run_page.wait_for_load_state()
    assert "/r/" in run_page.url and "/micromail" in run_page.url

    with httpx.Client(base_url=base_url, timeout=30) as api:
        spec = api.get(f"/api/scenarios/{SCENARIO_ID}/").json()
        assert [(e["time"], e["type"], e["payload"]) for e in spec["events"]] == [
            (12.0, "new_email", {"email_id": "base-04"})
        ]
        run = api.post("/api/runs/", json={"scenario": SCENARIO_ID, "clock_mode": "virtual"}).json()
        played = api.post(f"/api/runs/{run['id']}/advance/", json={"time": 60}).json()
        assert [(e["time"], e["type"]) for e in played["processed_events"]] == [(12.0, "new_email")]
