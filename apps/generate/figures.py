"""How diverse a generated set is: the figures `manage.py generate` prints.

Distinct prompts and trigger items (the catalog item whose arrival meets the condition), the
condition times per 100-second bin (apps.scenarios.spread, the rule `checkscenarios` applies),
the share of no-ops, and the share of each kind and family.
"""

from __future__ import annotations

from collections import Counter
from typing import Any

from apps.scenarios.format import parse_scenario
from apps.scenarios.spread import MAX_BIN_SHARE, condition_spread


def diversity(entries: list[dict[str, Any]], documents: list[dict[str, Any]]) -> list[str]:
    """The figures as printed lines (empty input: one line saying so)."""
    total = len(entries)
    if not total:
        return ["generated: 0 scenarios"]
    prompts = {d["prompt"] for d in documents}
    triggers = {(e["environment"], e["trigger_item"]) for e in entries if e["trigger_item"]}
    targeted = sum(1 for e in entries if e["kind"] != "noop")
    kinds = Counter(e["kind"] for e in entries)
    families = Counter((e["environment"], e["family"]) for e in entries)
    spread = condition_spread(parse_scenario(d, source=d["id"]) for d in documents)

    def share(n: int) -> str:
        return f"{n} ({100 * n / total:.1f} %)"

    lines = [
        f"generated: {total} scenarios, {targeted} targeted, no-ops {share(kinds['noop'])}",
        f"distinct prompts: {len(prompts)}; distinct trigger items: {len(triggers)}",
        "kinds: " + ", ".join(f"{k} {share(n)}" for k, n in sorted(kinds.items())),
        "condition_at per 100 s bin: "
        + ", ".join(f"{b.label} {b.count} ({100 * b.share:.0f} %)" for b in spread.bins),
        "condition_at spread: "
        + (
            "crowded: " + ", ".join(b.label for b in spread.crowded)
            if spread.crowded
            else f"ok: no bin above {100 * MAX_BIN_SHARE:.0f} %"
        ),
        f"families: {len(families)}",
    ]
    by_env: dict[str, list[str]] = {}
    for (environment, family), n in sorted(families.items()):
        by_env.setdefault(environment, []).append(f"{family} {n}")
    lines += [f"  {environment}: {', '.join(names)}" for environment, names in by_env.items()]
    return lines
