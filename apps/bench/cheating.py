"""What `bench validate` and the generator's in-memory proofs both refuse: a scenario that the
strategies of agents that never monitor can pass."""

from __future__ import annotations

from collections.abc import Callable


def cheating_problems(
    passed: Callable[[str, str], bool | None],
    ids: list[str],
    noop: set[str],
    active: list[str],
    noop_rule: str,
) -> list[str]:
    """What the strategies of agents that never monitor must not earn: an active task by acting
    on everything, or with no action at all (a fixed-time contact); any task by quitting; a
    no-op, which each of them either contacts in or quits (under the original's looser rule
    quitting passes no-ops: expected)."""
    why = {
        "act_all": "acting on every item is rewarded",
        "fixed_time": "a contact with no action is rewarded",
    }
    problems = [f"{a} passed {i} ({why[a]})" for a in why for i in active if passed(a, i)]
    problems += [f"{a} passed no-op {i}" for a in why for i in sorted(noop) if passed(a, i)]
    quitting_passes = noop if noop_rule == "original" else set()
    problems += [
        f"quitter passed {i} (leaving at once is rewarded)"
        for i in ids
        if passed("quitter", i) and i not in quitting_passes
    ]
    return problems
