"""An author asks the admin for variants of a scenario and reviews what it wrote."""

from __future__ import annotations

import io
import json

import pytest
from django.contrib.auth import get_user_model
from django.core.management import call_command

from apps.scenarios.models import Scenario
from tests.browser_story import admin_page
from tests.conftest import OUR_SCENARIOS

pytestmark = [pytest.mark.browser, pytest.mark.django_db(transaction=True)]

AUTHOR, PASSWORD = "grace", "correct horse battery staple"


@pytest.fixture
def sender_scenario(own_scenarios, live_site):
    """Our scenarios loaded into the admin, and an author (before the browser starts: the ORM
    refuses to work in Playwright's event-loop thread)."""
    get_user_model().objects.create_superuser(AUTHOR, "grace@example.test", PASSWORD)
    call_command("loadscenarios", str(OUR_SCENARIOS), stdout=io.StringIO(), stderr=io.StringIO())
    scenario = Scenario.objects.get(path="micromail/sender-absolute-passive.json")
    return live_site, own_scenarios, scenario.pk


def test_generate_variants_writes_proven_scenarios_the_author_can_open(sender_scenario, browser):
    live_site, folder, pk = sender_scenario
    page = admin_page(browser, live_site, AUTHOR, PASSWORD)
    page.goto(f"{live_site}/admin/scenarios/scenario/{pk}/change/")
    page.click("#variants-link")

    page.fill("#id_count", "2")
    page.fill("#id_seed", "3")
    page.uncheck("input[name=vary][value=phrasing]")  # the prompt stays the author's
    page.uncheck("input[name=vary][value=trigger]")  # and so does the trigger
    page.click("#generate-variants")

    page.wait_for_selector("#variants-summary")
    assert page.locator("#variants-summary").inner_text().startswith("2 proven variants written")
    links = page.locator("#variants-table a")
    assert links.all_inner_texts() == [
        "micromail-sender-absolute-passive-g3-0001",
        "micromail-sender-absolute-passive-g3-0002",
    ]
    written = [
        json.loads((folder / "micromail" / f"sender-absolute-passive-g3-000{n}.json").read_text())
        for n in (1, 2)
    ]
    original = json.loads((folder / "micromail" / "sender-absolute-passive.json").read_text())
    for scenario in written:
        assert scenario["prompt"] == original["prompt"]
        assert scenario["eval_sql"] == original["eval_sql"]
        assert scenario["condition_at"] != original["condition_at"]
        trigger = [e for e in scenario["events"] if e["time"] == scenario["condition_at"]]
        assert trigger[-1]["payload"] == {"email_id": "base-77"}  # Kevin Lee's mail, moved

    links.first.click()  # reviewable and editable as any scenario
    page.wait_for_selector("#id_prompt")
    assert "Kevin Lee" in page.locator("#id_prompt").input_value()
    assert page.locator("#id_scenario_id").input_value() == written[0]["id"]
