"""Regressions for the contradictions a real-browser walk found (issue 28), each on the page it
was seen on, rendered by the environment's own views in memory (apps.kit.probe). The generic
count test (test_shown_counts.py) keeps the rest of each page honest."""

from __future__ import annotations

import re
from pathlib import Path

from django.conf import settings

from apps.kit.probe import probe_run, render_probe, state_at_time
from apps.kit.visible import visible_text
from apps.scenarios.format import load_scenario_file
from events.registry import get_environment

SCENARIOS = Path(settings.SENTINEL_SCENARIO_DIR)


def world(name: str, file: str, now: float):
    scenario = load_scenario_file(SCENARIOS / name / file)
    return scenario, state_at_time(name, scenario.events, now)


def page_text(name: str, scenario, state, now: float, path: str) -> str:
    return visible_text(render_probe(probe_run(name, scenario.to_run_spec()), state, now, path))


def test_microdin_connections_read_the_same_on_home_my_network_and_the_list():
    """Was: "Connections 412" on the home page, "10" on My Network (the list's length)."""
    scenario, network = world("microdin", "dev.json", 60.0)
    for path in ("", "mynetwork/", "mynetwork/connections/"):
        text = page_text("microdin", scenario, network, 60.0, path)
        assert "Connections 412" in text, path
    connections = page_text("microdin", scenario, network, 60.0, "mynetwork/connections/")
    assert "412 Connections" in connections


def test_microdin_a_job_posted_minutes_ago_has_no_applicant_count_yet():
    """Was: a job posted "now" already had its catalogued 29 applicants."""
    scenario, network = world("microdin", "jobs-absolute-passive.json", 197.0)
    text = page_text("microdin", scenario, network, 197.0, "jobs/?job=job-13")
    assert "Mobile Engineer" in text and "Be among the first 25 applicants" in text
    assert "now ago" not in text
    preloaded = page_text("microdin", scenario, network, 197.0, "jobs/?job=job-01")
    assert re.search(r"\d+ applicants", preloaded)  # up before the run: its count


def test_microhub_starred_count_and_about_box_agree_after_starring():
    """Was: "Starred 1,325" in the header beside "1,324 stars" in the About box."""
    scenario, hub = world("microhub", "dev.json", 300.0)
    environment = get_environment("microhub")
    for now in (300.0, 300.5, 301.0, 457.25):
        starred = environment.perform(hub, "star", {}, now).state
        text = page_text("microhub", scenario, starred, now, "")
        header = re.search(r"Starred ([\d,]+)", text)
        about = re.search(r"([\d,]+) stars", text)
        assert header and about and header.group(1) == about.group(1), now


def test_microlendar_an_invitation_for_a_day_not_on_screen_is_noticed_until_opened():
    """Was: the Hawaii invitation landed on 13 October while the month view showed September,
    and nothing on the page changed. Now the sidebar lists it until it is opened."""
    scenario, agenda = world("microlendar", "description-hawaii-absolute-active.json", 541.0)
    text = page_text("microlendar", scenario, agenda, 541.0, "")
    assert "September 2025" in text
    assert re.search(r"New invitations \d+ Out of office Mon, Oct 13", text)
    opened = (
        get_environment("microlendar")
        .perform(agenda, "view_event", {"event_id": "desc-hawaii"}, 541.0)
        .state
    )
    assert "Out of office Mon, Oct 13" not in page_text("microlendar", scenario, opened, 541.0, "")
