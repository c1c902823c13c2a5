"""A scenario author in a real browser: log in, move an event, dry run, see the warning and chart."""

from __future__ import annotations

import io

import pytest
from django.contrib.auth import get_user_model
from django.core.management import call_command

from apps.scenarios.models import Scenario
from tests.browser_story import admin_page
from tests.conftest import OUR_SCENARIOS

pytestmark = [pytest.mark.browser, pytest.mark.django_db(transaction=True)]

AUTHOR, PASSWORD = "ada", "correct horse battery staple"


@pytest.fixture
def inbox_scenario(own_scenarios, live_site):
    """Our scenarios loaded, and an author who may log in. Set up before the browser starts:
    Playwright's sync API runs an event loop in this thread, where the ORM refuses to work."""
    get_user_model().objects.create_superuser(AUTHOR, "ada@example.test", PASSWORD)
    call_command("loadscenarios", str(OUR_SCENARIOS), stdout=io.StringIO(), stderr=io.StringIO())
    scenario = Scenario.objects.get(path="micromail/inbox-relative-passive.json")
    # cc-03, the fifth new inbox mail, at 173.64 s
    trigger_time = scenario.timeline.get(position=8).time
    return live_site, scenario.pk, trigger_time, scenario.timeline.count()


def test_an_author_moves_the_trigger_event_and_the_dry_run_flags_it(inbox_scenario, browser):
    # The server comes from inbox_scenario, started after own_scenarios: a server started first
    # would write the edit into the copy every other test of the session plays.
    live_site, pk, trigger_time, event_count = inbox_scenario
    page = admin_page(browser, live_site, AUTHOR, PASSWORD)
    page.goto(f"{live_site}/admin/scenarios/scenario/{pk}/change/")
    assert page.locator("#timeline-chart").is_visible()

    time_input = page.locator(f"input[name$='-time'][value='{trigger_time}']")
    assert time_input.count() == 1
    time_input.fill("203.64")
    page.click("#save-and-dry-run")

    page.wait_for_selector("#dry-run-warnings")
    warning = page.locator("#dry-run-warnings").inner_text()
    assert "first holds at 203.64 s, but condition_at is 173.64 s" in warning
    chart = page.locator("#timeline-chart")
    assert chart.is_visible()
    assert chart.locator("g.condition-at").count() == 1 and chart.locator("g.kill-at").count() == 1
    assert chart.locator("g.event").count() == event_count
    assert "203.64" in page.locator("#dry-run-table").inner_text()  # the edit was saved
