"""The first hour's error messages: each says what is wrong, where, in one line."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time

import pytest

from apps.bench.client import ControlClient
from apps.bench.management.commands.bench import Command as BenchCommand
from apps.bench.runner import discover
from apps.tally.environment import tally_scenario
from tests.conftest import REPO

pytestmark = pytest.mark.django_db


def test_a_json_body_without_content_type_is_read_as_json(api):
    body = json.dumps({"scenario_json": tally_scenario(), "speed_factor": 2})
    response = api.generic("POST", "/api/runs/", body, content_type="")
    assert response.status_code == 201, response.content
    assert response.json()["speed_factor"] == 2
    broken = api.generic("POST", "/api/runs/", "{not json", content_type="")
    assert broken.status_code == 400
    assert "Content-Type: application/json" in broken.json()["detail"]


def test_an_unknown_action_is_a_400_naming_the_allowed_actions(api):
    run = api.post("/api/runs/", {"scenario_json": tally_scenario()}, format="json").json()
    response = api.post(f"/r/{run['token']}/actions", {"action": "kick"}, format="json")
    assert response.status_code == 400
    assert response.json()["detail"] == "unknown action 'kick' for tally; allowed: poke"


def test_a_later_post_to_contact_has_its_own_time(api):
    run = api.post(
        "/api/runs/", {"scenario_json": tally_scenario(), "speed_factor": 4}, format="json"
    ).json()
    api.get(f"/r/{run['token']}/start")  # starts the live clock
    assert api.get(f"/r/{run['token']}/contact").status_code == 200
    time.sleep(0.3)  # the agent reads the form, then submits it
    assert api.post(f"/r/{run['token']}/contact", {"message": "done"}).status_code == 200
    verdict = api.post(f"/api/runs/{run['id']}/evaluate/").json()
    assert verdict["contact_post_time"] > verdict["contact_get_time"]
    assert verdict["contact_message"] == "done"


@pytest.mark.slow
def test_an_unreachable_database_is_one_line():
    env = {k: v for k, v in os.environ.items() if not k.startswith(("DJANGO_", "SENTINEL_"))}
    env["DATABASE_URL"] = "postgres://sentinel@127.0.0.1:1/sentinel"
    done = subprocess.run(
        [sys.executable, "manage.py", "migrate"],
        cwd=REPO,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 1
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("database error: "), done.stderr
    assert "127.0.0.1" in lines[0] and "DATABASE_URL" in lines[0]


@pytest.mark.slow
def test_task_given_twice_selects_both(live_site):
    parser = BenchCommand().create_parser("manage.py", "bench")
    options = parser.parse_args(["run", "n", "--task", "a", "--task", "b"])
    assert options.task == ["a", "b"]
    client = ControlClient(live_site)
    try:
        wanted = ["micromail-junk-relative-passive", "micromail/inbox-relative-passive.json"]
        selected = discover(client, task=wanted)
        assert [entry["id"] for entry in selected] == [
            "micromail-inbox-relative-passive",
            "micromail-junk-relative-passive",
        ]
    finally:
        client.close()
