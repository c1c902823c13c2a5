"""The admin's "Generate variants…": proven variants of one scenario, kept as new files.

The author picks how many, what to vary (timing, distractors, phrasing) and a seed; the
scenario as saved is the template (apps.generate: the same draws and proofs as
`manage.py generate`). Each proven variant is written beside it as an ordinary scenario file,
`<environment>/<family>-g<seed>-<nnnn>.json`, and imported, so the author reviews, edits, runs
or deletes it like any other; a path already taken is left alone and reported.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from django import forms

from apps.generate.compose import ASPECTS
from apps.generate.generate import MAX_VARIANTS, GenerationError, variants
from apps.generate.templates import template_of
from apps.scenarios.format import ScenarioError
from apps.scenarios.models import Scenario
from apps.scenarios.serialization import (
    parsed_scenario,
    render_json,
    save_scenario_file,
    scenario_document,
    scenario_file_of,
    timeline_of,
)
from apps.scenarios.sync import ScenarioFileError, write_through


class VariantsForm(forms.Form):
    count = forms.IntegerField(label="How many", min_value=1, max_value=MAX_VARIANTS, initial=5)
    vary = forms.MultipleChoiceField(
        label="Vary",
        choices=[(a, a) for a in ASPECTS],
        initial=list(ASPECTS),
        widget=forms.CheckboxSelectMultiple,
        help_text="timing: a new condition time, the background re-timed; distractors: other "
        "and added catalog items, near misses first; phrasing: the prompt reworded; trigger: "
        "another catalog item of its kind as the trigger",
    )
    seed = forms.IntegerField(label="Seed", min_value=0, initial=1)


@dataclass
class VariantsOutcome:
    created: list[Scenario] = field(default_factory=list)
    skipped: list[str] = field(default_factory=list)  # paths already taken
    candidates: int = 0
    discarded: dict[str, int] = field(default_factory=dict)  # reason -> count
    problem: str = ""  # why nothing could be generated


def generate_variants(scenario: Scenario, *, count: int, vary: list[str], seed: int):
    """Generate, prove and keep variants of `scenario` (see the module doc)."""
    outcome = VariantsOutcome()
    try:
        parsed_scenario(scenario)
    except ScenarioError as error:
        outcome.problem = f"the scenario does not load: {error}"
        return outcome
    if scenario.is_dev:
        outcome.problem = "a dev.json populates everything: it has no task to vary"
        return outcome
    document = scenario_document(scenario, timeline_of(scenario))
    template = template_of(document, scenario.environment, scenario.path)
    aspects = tuple(a for a in ASPECTS if a in vary)
    try:
        result = variants(template, seed=seed, count=count, aspects=aspects)
    except GenerationError as error:
        outcome.problem = str(error)
        return outcome
    outcome.candidates = result.candidates
    outcome.discarded = dict(result.discarded.most_common())
    if result.unprovable:
        outcome.problem = "the scenario itself fails a proof: " + next(
            iter(result.unprovable.values())
        )
    for entry, generated in zip(result.entries, result.documents, strict=True):
        path = entry["file"]
        if Scenario.objects.filter(path=path).exists():
            outcome.skipped.append(path)
            continue
        scenario_file = scenario_file_of(generated, render_json(generated), path, source=path)
        row = save_scenario_file(scenario_file)
        try:
            write_through(row)
        except ScenarioFileError as error:
            row.delete()
            outcome.problem = str(error)
            break
        outcome.created.append(row)
    return outcome
