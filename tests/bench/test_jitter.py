"""`bench run --jitter S --seed N`: each trial's whole timeline shifted by its own amount, drawn
from the seed, so repeated trials do not share one trigger time; the oracle still passes them."""

from __future__ import annotations

import io
import json

import pytest
from django.core.management import call_command

from apps.bench.runner import shift_bounds, shifted, timeline_shift
from tests.bench.conftest import shorten

SCENARIO = {
    "id": "s",
    "condition_at": 40.0,
    "kill_at": 60.0,
    "event_timeline_end": 100.0,
    "events": [{"time": 0, "type": "preload"}, {"time": 12.0, "type": "a"}, {"time": 40.0, "type": "b"}],
}  # fmt: skip


def test_the_whole_timeline_moves_and_the_preload_stays():
    moved = shifted(SCENARIO, 7.5)
    assert [e["time"] for e in moved["events"]] == [0, 19.5, 47.5]
    assert (moved["condition_at"], moved["kill_at"], moved["event_timeline_end"]) == (
        47.5,
        67.5,
        107.5,
    )


def test_shifts_keep_the_condition_in_the_papers_range_and_entries_after_the_preload():
    assert shift_bounds(SCENARIO) == (-6.0, 560.0)  # the 12 s entry stays after t=0
    shifts = {timeline_shift(SCENARIO, 300, seed=1, trial=n) for n in range(1, 50)}
    assert all(-6.0 <= s <= 300 for s in shifts) and len(shifts) == 49
    assert timeline_shift(SCENARIO, 300, 1, 3) == timeline_shift(SCENARIO, 300, 1, 3)
    assert timeline_shift(SCENARIO, 300, 1, 3) != timeline_shift(SCENARIO, 300, 2, 3)


@pytest.fixture
def one_scenario(tmp_path, settings):
    root = tmp_path / "scenarios"
    (root / "micromail").mkdir(parents=True)
    data = shorten("sender-absolute-passive", "bench-jitter", "", condition_at=16, kill_at=28)
    (root / "micromail" / "bench-jitter.json").write_text(json.dumps(data))
    settings.SENTINEL_SCENARIO_DIR = root
    return root


@pytest.mark.django_db(transaction=True)
@pytest.mark.e2e
def test_two_trials_get_two_shifts_and_the_oracle_passes_both(one_scenario, tmp_path):
    results = tmp_path / "results"
    out = io.StringIO()
    call_command(
        "bench", "run", "jittered", "--agent", "oracle", "--trials", "2", "--parallel", "2",
        "--jitter", "8", "--seed", "7", "--speed-factor", "4", "--results-dir", str(results),
        stdout=out,
    )  # fmt: skip
    task = results / "jittered" / "micromail" / "bench-jitter"
    trials = [
        json.loads((folder / "results.json").read_text()) for folder in (task, task / "trial-2")
    ]
    shifts = [t["timeline_shift"] for t in trials]
    assert shifts[0] != shifts[1] and all(-8 <= s <= 8 for s in shifts)
    assert [t["success"] for t in trials] == [True, True], out.getvalue()
    # The run played the shifted timeline: its condition (wall s at speed 4) moved with it.
    assert [t["condition_at"] for t in trials] == [(16 + s) / 4 for s in shifts]
    manifest = json.loads((results / "jittered" / "manifest.json").read_text())
    assert manifest["config"]["jitter"] == 8 and manifest["config"]["seed"] == 7
    assert list(manifest["config"]["timeline_shifts"].values()) == shifts
