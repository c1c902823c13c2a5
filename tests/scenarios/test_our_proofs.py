"""Our scenarios proven as `bench validate` proves them, played in memory (apps.generate.proofs,
the generator's proofs): every one passes, and the figures are the README's.
tests/bench/test_readme_examples.py holds the in-memory play to the harness's own verdicts."""

from __future__ import annotations

import json
import re

import pytest

from apps.generate.proofs import Proof, prove
from apps.scenarios.library import library
from apps.scenarios.watching import unseen_triggers
from tests.conftest import OUR_SCENARIOS, REPO

README_FIGURES = re.compile(r"^bench_validate: scenarios=\d+ .*$", re.M)
SPEED, WINDOW = 4.0, 30.0  # bench validate's defaults, which the README's command keeps


def readme_validate_figures() -> str:
    """The README's `bench validate` figures on our scenarios, without the run's wall time."""
    line = README_FIGURES.search((REPO / "README.md").read_text(encoding="utf-8")).group(0)
    return line.split(" wall_s=")[0]


def proven_in_memory(environment: str | None = None) -> dict[str, tuple[dict, Proof]]:
    """Every scenario of ours (or of one environment), as the server loads it, with its proofs
    played in memory."""
    loaded = library(OUR_SCENARIOS).by_path
    documents = [json.loads((OUR_SCENARIOS / path).read_text()) for path in loaded]
    return {
        doc["id"]: (doc, prove(doc))
        for doc in documents
        if environment in (None, doc["environment"])
    }


def figures_of(proven: dict[str, tuple[dict, Proof]], unseen: int) -> str:
    """bench validate's last line (less its wall time and clock), from in-memory proofs."""
    ids = list(proven)
    condition = {i: doc["condition_at"] for i, (doc, _) in proven.items()}
    targeted = [i for i in ids if condition[i] is not None]

    def passed(agent: str, among: list[str]) -> int:
        return sum(proven[i][1].verdicts[agent] for i in among)

    def timely(agent: str) -> int:  # a pass reported within the reaction window (wall s)
        return sum(
            proof.verdicts[agent] and (proof.reports[agent] - condition[i]) / SPEED <= WINDOW
            for i in targeted
            for proof in [proven[i][1]]
        )

    never_ok = sum(
        proof.verdicts["never"] is (condition[i] is None) for i, (_, proof) in proven.items()
    )
    cheats = " ".join(
        f"{agent}={passed(agent, ids)}/{len(ids)} {agent}_timely={timely(agent)}/{len(targeted)}"
        for agent in ("act_all", "fixed_time", "quitter")
    )
    ephemeral = [i for i, (doc, _) in proven.items() if doc.get("condition_until") is not None]
    return (
        f"bench_validate: scenarios={len(ids)} oracle={passed('oracle', ids)}/{len(ids)} "
        f"early_fail={len(targeted) - passed('early', targeted)}/{len(targeted)} "
        f"never_ok={never_ok}/{len(ids)} sleeper={passed('sleeper', ids)}/{len(ids)} {cheats} "
        f"late_ephemeral={passed('late', ephemeral)}/{len(ephemeral)} "
        f"unseen={unseen}/{len(targeted)}"
    )


@pytest.mark.slow
def test_our_scenarios_proven_in_memory_give_the_readme_validate_figures():
    """The README's figures for `bench validate` on all our scenarios, from the same control
    agents played in memory (apps.generate.proofs), which the next test holds to the harness's
    verdicts; and the watched-page check `bench validate` runs."""
    proven = proven_in_memory()
    unseen = unseen_triggers(library(OUR_SCENARIOS).by_path.values())
    assert not [(i, proof.problems) for i, (_, proof) in proven.items() if proof.problems]
    assert figures_of(proven, len(unseen)) == readme_validate_figures()
