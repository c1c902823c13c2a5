"""One reaction time: from the condition to the agent's first contact of either kind. An agent
that reports by POSTing the contact form alone (no GET) is timely, and `bench grade` gives it the
very reaction time the server's verdict does."""

from __future__ import annotations

import io
import json

import pytest
from django.core.management import call_command

from apps.bench.grading import load_rows, reaction_time_of
from tests.bench.conftest import shorten

pytestmark = [pytest.mark.django_db(transaction=True), pytest.mark.e2e]


@pytest.fixture
def post_only_scenario(tmp_path, settings):
    root = tmp_path / "scenarios"
    (root / "micromail").mkdir(parents=True)
    data = shorten(
        "sender-absolute-passive", "bench-post-only", "poll select-base-77; post-contact"
    )
    (root / "micromail" / "bench-post-only.json").write_text(json.dumps(data))
    settings.SENTINEL_SCENARIO_DIR = root
    return root


def test_a_post_only_contact_has_the_servers_reaction_time_in_bench_grade(
    post_only_scenario, bench_config, tmp_path
):
    results = tmp_path / "results"
    call_command(
        "bench", "run", "post-only", "--config", str(bench_config()),
        "--results-dir", str(results), stdout=io.StringIO(),
    )  # fmt: skip
    folder = results / "post-only" / "micromail" / "bench-post-only"
    verdict = json.loads((folder / "results.json").read_text())
    assert verdict["success"] is True
    assert verdict["contact_get_time"] is None and verdict["contact_post_time"] is not None
    assert verdict["reaction_time"] is not None
    (row,) = load_rows(results / "post-only")
    assert row.reaction_time == verdict["reaction_time"]
    assert row.stop_time == verdict["contact_post_time"]
    assert row.timely(window=4)  # the config's reaction window


def test_a_result_of_the_original_harness_gets_the_same_rule():
    # No `reaction_time` in it: the first contact of either kind, here the POST.
    upstream = {"success": True, "condition_at": 10.0, "contact_get_time": None,
                "contact_post_time": 12.5}  # fmt: skip
    assert reaction_time_of(upstream) == 2.5
    assert reaction_time_of({**upstream, "contact_get_time": 11.0}) == 1.0
    assert reaction_time_of({**upstream, "success": False}) is None
