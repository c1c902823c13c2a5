"""One truth per number, in every environment: each count an environment declares
(`Environment.shown_counts`, apps.kit.counts) reads the same on every sample page that shows it.

The pages are the environment's `sample_pages` over its dev.json world (everything loaded), at
two moments of the clock; rendered by the environment's own views in memory (apps.kit.probe).
"""

from __future__ import annotations

from pathlib import Path

import pytest
from django.conf import settings

from apps.kit.counts import appearances, disagreements
from apps.kit.probe import probe_run, render_probe, state_at_time
from apps.kit.visible import visible_text
from apps.scenarios.format import SENTINELBENCH_ENVIRONMENTS, load_scenario_file
from events.registry import get_environment

MOMENTS = (120.0, 480.0)  # simulated seconds: early in a run, and late


def sample_texts(name: str, now: float):
    """(state, [(path, visible text)]) of every sample page of `name`'s dev world at `now`."""
    dev = load_scenario_file(Path(settings.SENTINEL_SCENARIO_DIR) / name / "dev.json")
    environment = get_environment(name)
    state = state_at_time(name, dev.events, now)
    run = probe_run(name, dev.to_run_spec())
    pages = environment.sample_pages(state)
    return state, [(path, visible_text(render_probe(run, state, now, path))) for path in pages]


@pytest.mark.parametrize("name", SENTINELBENCH_ENVIRONMENTS)
@pytest.mark.parametrize("now", MOMENTS)
def test_every_declared_count_reads_the_same_on_every_sample_page(name, now):
    counts = get_environment(name).shown_counts
    assert counts, f"{name} declares no shown_counts"
    state, texts = sample_texts(name, now)
    problems = [p for path, text in texts for p in disagreements(counts, state, now, path, text)]
    assert problems == []
    shown = set().union(*(appearances(counts, state, path, text) for path, text in texts))
    # A zero is often not written at all (no badge): only a count that is not may go unseen.
    nonzero = {
        count.name
        for count in counts
        if any(count.on(state, path) and count.value_at(state, now, path) for path, _ in texts)
    }
    assert nonzero <= shown, "declared, not zero, and shown on no sample page"
