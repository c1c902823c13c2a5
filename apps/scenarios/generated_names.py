"""How generated scenarios are named: `<environment>-<family>-g<seed>-<nnnn>`, so that `bench
grade` can report by family from a result's scenario id alone (no import of the generator)."""

from __future__ import annotations

import re

GENERATED_ID = re.compile(r"^(?P<environment>[a-z0-9]+)-(?P<family>.+)-g(?P<seed>\d+)-\d{4}$")


def generated_id(environment: str, family: str, seed: int, number: int) -> str:
    return f"{environment}-{family}-g{seed}-{number:04d}"


def family_of(scenario_id: str) -> str | None:
    """The family of a generated scenario's id (`bench grade` reports by it); None otherwise."""
    match = GENERATED_ID.match(scenario_id)
    return match["family"] if match else None
