"""Benchmark fast-forward: the reference agents on fast_forward clocks against live ones.

`bench run` with a reference agent whose model is the scripted server, on every scenario (or
`--subset`: two per environment, the first targeted and the first no-op) with `--clock
fast-forward`; with `--compare`, the subset again on live clocks at speed 1, and the two graded
task by task: the same verdict, reaction times within `--tolerance` simulated seconds, the same
number of model calls. Prints one `bench_fast_forward:` line per run and one per comparison.
The fast-forward runs are paced (`--awake`, sentinel_site/pacing.py): the scripted model costs
nothing, so the agents' work is all this machine's, and unpaced ten of them on two cores each
work at a fifth of its speed, in simulated seconds as a live agent would. By default one agent
fewer than the machine has cores is awake (at least one): the core left over takes what pacing
does not hold — the next agents' browsers starting, the harness grading — off the awake agents'
path from a look to an action (on two cores, two awake left reaction times 1.1–2.1 s from the
live ones, one awake 0.8–0.95 s).

The script: `wait_for` watches the start page until the task's change (its judge says yes on
a change adding a phrase of any scenario's condition entry: the subject, title or text its
catalog record starts with), then contacts, else terminates; `sleep` sleeps 250 s, reads the
page, sleeps again and terminates. Both are deterministic, so whatever differs between the two
clocks is the clock's doing.
"""

from __future__ import annotations

import io
import json
import os
import tempfile
import time
from pathlib import Path
from typing import Any

import yaml
from django.conf import settings
from django.core.management import call_command
from django.core.management.base import BaseCommand, CommandError

from apps.bench.layout import COSTS, agent_files
from apps.browser_agent.scripted_model import parse_script, scripted_model_server
from apps.scenarios.library import scenario_library

MODEL = "scripted"
TEXT_FIELDS = ("subject", "title", "name", "headline", "content", "text", "body", "description")
PHRASE_CHARS = 24
# The wait outlasts a no-op task's run (600 s: the paper's rule has the agent stay to its end),
# and its final check and the contact after it still fall inside the agent's budget (its
# deadline, 630 s) when a loaded machine starts the agent up to 25 s late: no verdict hangs on
# whether the budget ran out between the two, which depends on load, not on the clock.
WAIT_TIMEOUT_S = 600.0
# Two sleeps well inside the budget even when a loaded machine starts the agent slowly: its
# turns, not the budget, decide how often it asks the model.
SLEEP_S = 250.0


def condition_phrases(scenarios: list[dict[str, Any]], catalog: Path) -> list[str]:
    """The start of the text of every catalog record a condition entry brings (pure)."""
    records: dict[tuple[str, str], dict] = {}
    for path in catalog.glob("*/*.jsonl"):
        for line in path.read_text(encoding="utf-8").splitlines():
            if line.strip():
                record = json.loads(line)
                if isinstance(record, dict) and "id" in record:
                    records[(path.parent.name, str(record["id"]))] = record
    phrases = []
    for spec in scenarios:
        condition = spec.get("condition_at")
        for entry in spec["events"] if condition is not None else ():
            if abs(entry["time"] - condition) > 1e-6:
                continue
            for value in (entry.get("payload") or {}).values():
                record = records.get((spec["environment"], str(value)))
                text = next((record[f] for f in TEXT_FIELDS if record and record.get(f)), None)
                if isinstance(text, str) and text.strip():
                    phrases.append(text.strip().splitlines()[0][:PHRASE_CHARS])
    return sorted(set(phrases))


def agent_script(kind: str, phrases: list[str]) -> dict[str, Any]:
    if kind == "sleep":
        turns = [
            {"call": "sleep", "arguments": {"seconds": SLEEP_S}},
            {"call": "read_page"},
            {"call": "sleep", "arguments": {"seconds": SLEEP_S}},
            {"call": "terminate", "arguments": {"reason": "done watching"}},
        ]
        return {"model": MODEL, "agent": turns}
    return {
        "model": MODEL,
        "agent": [
            {
                "call": "wait_for",
                "arguments": {"condition": "what the task waits for", "timeout": WAIT_TIMEOUT_S},
            },
            {
                "when_last_result": "met: true",
                "call": "contact",
                "arguments": {"message": "It has happened."},
            },
            {"otherwise": True, "call": "terminate", "arguments": {"reason": "it did not happen"}},
        ],
        "judge": {"yes_when_any": phrases},
    }


def two_per_environment(scenarios: list[dict[str, Any]]) -> list[str]:
    """Two per environment: its first targeted scenario (passive first) and its first no-op."""
    chosen = []
    for environment in sorted({s["environment"] for s in scenarios}):
        mine = [s for s in scenarios if s["environment"] == environment]
        targeted = [s for s in mine if s.get("condition_at") is not None]
        targeted.sort(key=lambda s: s.get("taxonomy", {}).get("monitoring_approach") != "passive")
        noops = [s for s in mine if s.get("condition_at") is None]
        chosen += [s["id"] for s in (targeted[:1] + noops[:1])]
    return chosen


def task_outcomes(folder: Path) -> dict[str, dict[str, Any]]:
    """scenario id → {success, reaction (simulated s), calls} of a results tree."""
    found = {}
    for path in folder.glob("*/*/results.json"):
        result = json.loads(path.read_text())
        costs_path = agent_files(path.parent) / COSTS
        costs = json.loads(costs_path.read_text()) if costs_path.exists() else {}
        stop, condition = result.get("contact_get_time"), result.get("condition_at")
        reaction = None
        if result.get("success") and stop is not None and condition is not None:
            reaction = (stop - condition) * float(result.get("speed_factor") or 1.0)
        found[result["scenario_id"]] = {
            "success": bool(result.get("success")),
            "reaction": reaction,
            "calls": costs.get("calls"),
        }
    return found


def comparison(fast: dict[str, dict], live: dict[str, dict], tolerance: float) -> dict[str, Any]:
    """How the fast-forward outcomes of the tasks both ran compare with the live ones (pure)."""
    both = sorted(set(fast) & set(live))
    differing = [t for t in both if fast[t]["success"] != live[t]["success"]]
    gaps = [
        abs(fast[t]["reaction"] - live[t]["reaction"])
        for t in both
        if fast[t]["reaction"] is not None and live[t]["reaction"] is not None
    ]
    calls = [t for t in both if fast[t]["calls"] != live[t]["calls"]]
    return {
        "tasks": len(both),
        "same_verdict": len(both) - len(differing),
        "differing": differing,
        "max_reaction_gap_s": max(gaps, default=0.0),
        "within_tolerance": all(gap <= tolerance for gap in gaps),
        "same_calls": len(both) - len(calls),
    }


class Command(BaseCommand):
    help = "Benchmark fast-forward clocks: wall time, and verdicts against live clocks."

    def add_arguments(self, parser):
        parser.add_argument("--kind", choices=("wait_for", "sleep"), default="wait_for")
        parser.add_argument("--parallel", type=int, default=10)
        parser.add_argument(
            "--live-parallel",
            type=int,
            default=None,
            help="tasks at a time on live clocks (default: --parallel); fewer keep a "
            "one-second watcher on time on a small machine",
        )
        parser.add_argument(
            "--subset", dest="subset_only", action="store_true", help="two per environment"
        )
        parser.add_argument(
            "--compare",
            dest="with_live",
            action="store_true",
            help="also the subset on live clocks at speed 1, compared task by task",
        )
        parser.add_argument(
            "--awake",
            type=int,
            default=max(1, (os.cpu_count() or 2) - 1),
            help="fast-forward agents working at once (bench run --awake; default: one fewer "
            "than the machine's cores, at least one; 0: no pacing)",
        )
        parser.add_argument("--tolerance", type=float, default=1.0, help="simulated seconds")
        parser.add_argument("--results-dir", default=None, help="default: a temporary folder")

    def handle(self, *args, kind, parallel, subset_only, with_live, tolerance, awake, **options):
        live_parallel = options["live_parallel"] or parallel
        for flag, value in (("--parallel", parallel), ("--live-parallel", live_parallel)):
            if value < 1:
                raise CommandError(f"{flag} must be >= 1, got {value}")
        if awake < 0:
            raise CommandError(f"--awake must be >= 0 (0: no pacing), got {awake}")
        library = scenario_library()
        scenarios = [library[name].to_run_spec() for name in sorted(library)]
        few = two_per_environment(scenarios)
        picked = few if subset_only else [s["id"] for s in scenarios]
        phrases = condition_phrases(scenarios, Path(settings.SENTINEL_CATALOG_DIR))
        root = Path(options["results_dir"] or tempfile.mkdtemp(prefix="bench-fast-forward-"))
        stamp = time.strftime("%Y%m%d-%H%M%S")
        with scripted_model_server(parse_script(agent_script(kind, phrases))) as model:
            config = root / f"{kind}.yaml"
            root.mkdir(parents=True, exist_ok=True)
            config.write_text(
                yaml.safe_dump(
                    {
                        "speed_factor": 1,
                        "agent": {"kind": kind, "model": MODEL, "base_url": model.base_url},
                    }
                )
            )
            fast = f"{kind}-fast-forward-{stamp}"
            wall = self.run(fast, config, root, parallel, picked, "fast_forward", awake)
            self.line(fast, root, wall, "fast_forward", len(picked), parallel, awake)
            if not with_live:
                return
            live = f"{kind}-live-{stamp}"
            wall_live = self.run(live, config, root, live_parallel, few, "live", 0)
            self.line(live, root, wall_live, "live", len(few), live_parallel, 0)
        result = comparison(task_outcomes(root / fast), task_outcomes(root / live), tolerance)
        self.stdout.write(
            f"bench_fast_forward: compare kind={kind} tasks={result['tasks']} "
            f"same_verdict={result['same_verdict']}/{result['tasks']} "
            f"max_reaction_gap_s={result['max_reaction_gap_s']:.2f} "
            f"same_model_calls={result['same_calls']}/{result['tasks']} "
            f"differing={','.join(result['differing']) or '-'}"
        )

    def run(self, name, config, root, parallel, tasks, clock, awake: int) -> float:
        argv = ["run", name, "--config", str(config), "--results-dir", str(root)]
        argv += ["--parallel", str(parallel), "--clock", clock, "--awake", str(awake)]
        for task in tasks:
            argv += ["--task", task]
        began = time.monotonic()
        out = io.StringIO()
        try:
            call_command("bench", *argv, stdout=out)
        finally:
            (root / f"{name}.log").write_text(out.getvalue())
        return time.monotonic() - began

    def line(
        self, name, root, wall: float, clock: str, count: int, parallel: int, awake: int
    ) -> None:
        outcomes = task_outcomes(root / name)
        passed = sum(o["success"] for o in outcomes.values())
        calls = sum(o["calls"] or 0 for o in outcomes.values())
        self.stdout.write(
            f"bench_fast_forward: run={name} clock={clock} tasks={count} parallel={parallel} "
            f"awake={awake} passed={passed} "
            f"model_calls={calls} wall_s={wall:.1f} results={root / name}"
        )
