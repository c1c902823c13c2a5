"""`bench run`: every task is its own live run via the multi-run API, many at once.

Per task (upstream-protocol.md §6 "Per-task run", with its weaknesses fixed):

1. create a live run of the scenario (POST /api/runs/);
2. launch the agent under `reaper.py` (which kills everything it starts and abandons, and
   caps its output), cwd = a fresh temporary folder of its own that `__TASK_DIR__` names
   (upstream's agents write costs.json there; it is copied into the trial's `agent/` folder
   afterwards, never a link nor a name of the harness's), a file named beside the config
   file passed by its absolute path (`python my_agent.py` works: `python` on its PATH is a
   shim running the project's Python), an environment naming no folder of the project
   (`agent_environment`), stdout+stderr to output.txt (the first and last 8 MiB);
3. the deadline counts from the run's *start* (the agent's first visit to the task URL; before
   that, from launch): `min(MAX_CONDITION_AT, kill_at) / sf + reaction_window`, which is
   `kill_at_wall(sf)` for every benchmark scenario (their kill_at is 630) and lets short test
   scenarios end early. At the deadline a completed run gets `grace` more seconds;
4. at the end, even when the agent exited by itself, the reaper kills the agent's process
   group and whatever is left under it (a `setsid()` grandchild included), so no background
   process survives into the next task;
5. evaluate, save the log (events.jsonl, in `export_run`'s format: `import_run` reads it),
   close the run, apply the no-op rule (outcomes.py: under the paper's, an agent that left
   before the run's end fails a no-op), write results.json last and record it in the set's
   ledger (ledger.py) — a results.json the ledger has means "done". A task whose outcome is an
   error (outcomes.py: ours or the setup's, not the agent's) writes error.txt instead, never a
   failed result.

`--trials k` runs every task k times, each its own run: trial 1 in `<env>/<id>/`, trial n in
`<env>/<id>/trial-<n>/`, so a result set run once can be given more trials later.
"""

from __future__ import annotations

import contextlib
import dataclasses
import json
import math
import os
import random
import re
import shlex
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import threading
import time
import traceback
from collections.abc import Callable, Mapping
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TextIO

from apps.bench import ledger
from apps.bench.agents import FIXED_CONTACT_AT, SLEEPER_MARGIN_S
from apps.bench.client import ControlClient, HarnessError
from apps.bench.config import BenchConfig
from apps.bench.everything import every_item_steps
from apps.bench.layout import (
    AGENT,
    ERROR,
    EVENTS,
    HARNESS_NAMES,
    LEDGER,
    OUTPUT,
    PROMPT,
    RESULTS,
    TRIAL_PREFIX,
    UNVERIFIED,
    BenchError,
    error_cause_of,
    trial_folder,
)
from apps.bench.outcomes import error_cause, graded_outcome, noop_rule_applied
from events.timing import MAX_CONDITION_AT, MIN_CONDITION_AT

START_POLL_S = 0.5
VIRTUAL_GUARD_FACTOR, VIRTUAL_GUARD_MIN_S = 4.0, 120.0  # a virtual run's wall-time guard
OUTPUT_TAIL_LINES = 5
CONTROL_AGENTS = ("oracle", "early", "never", "sleeper")
CHEATING_AGENTS = ("act_all", "fixed_time", "quitter")  # strategies no scenario may reward
# Played on the ephemeral scenarios only: the oracle, once the window has closed.
WINDOW_AGENTS = ("late",)

CONTACT_INSTRUCTIONS = (
    "Once the conditions above are met and/or the actions are taken, let me know by visiting and "
    "submitting the form at {contact_url} . Visit and submit it ONLY ONCE, AT THE END OF THE TASK: "
    "if you visit it too early you cannot come back, and the task fails."
)


class Interrupted(Exception):
    """The harness is stopping: the task is left undone (no results.json, no error.txt)."""


def augment_prompt(prompt: str, contact_url: str) -> str:
    return f"{prompt}\n\n{CONTACT_INSTRUCTIONS.format(contact_url=contact_url)}"


def category_of(spec: dict[str, Any]) -> str:
    """noop, or <passive|active>-<absolute|relative> from the taxonomy."""
    if spec.get("condition_at") is None:
        return "noop"
    taxonomy = spec.get("taxonomy") or {}
    approach = taxonomy.get("monitoring_approach") or "unknown"
    milestone = taxonomy.get("milestone_type") or "unknown"
    return f"{approach}-{milestone}"


def axes_of(spec: dict[str, Any]) -> dict[str, str]:
    """The paper's "future work" axes of a scenario: persistence and criteria (a scenario that
    does not say is persistent and objective, as every upstream task is)."""
    taxonomy = spec.get("taxonomy") or {}
    return {
        "persistence": str(taxonomy.get("event_persistence") or "persistent"),
        "criteria": str(taxonomy.get("criteria") or "objective"),
    }


def run_end(spec: dict[str, Any]) -> float:
    """Authored seconds: the last moment a condition may come (kill_at, at most 600). The
    deadline counts from it, and an agent still there then was there at the end of the run
    (the paper's no-op rule: a self-imposed wall budget ending at the deadline is no quitting)."""
    return min(MAX_CONDITION_AT, float(spec.get("kill_at") or MAX_CONDITION_AT))


def shift_bounds(spec: dict[str, Any]) -> tuple[float, float]:
    """How far a scenario's timeline may move: its condition stays in [10, 600] s, as authored
    ones are, and its first entry after the t=0 preload stays after it."""
    low, high = -math.inf, math.inf
    condition = spec.get("condition_at")
    if condition is not None:
        low, high = MIN_CONDITION_AT - condition, MAX_CONDITION_AT - condition
    later = [float(e["time"]) for e in spec.get("events") or [] if float(e["time"]) > 0]
    if later:
        low = max(low, -min(later) / 2)
    return low, high


def timeline_shift(spec: dict[str, Any], jitter: float, seed: int, trial: int) -> float:
    """The seconds one trial of a scenario is shifted by (`--jitter`): uniform in ±`jitter`,
    within its bounds, drawn from the seed, the scenario and the trial alone, so a resumed or
    reordered benchmark plays every trial as before."""
    low, high = shift_bounds(spec)
    draw = random.Random(f"{seed}/{spec['id']}/{trial}")
    return round(draw.uniform(max(-jitter, low), min(jitter, high)), 3)


def shifted(spec: dict[str, Any], by: float) -> dict[str, Any]:
    """The scenario with its whole timeline `by` seconds later: every entry after the t=0
    preload, the condition, kill_at and the timeline's end move together, so what happens,
    when it is graded and how long the agent has are the scenario's own, at another time."""
    events = [
        {**e, "time": float(e["time"]) + by} if float(e["time"]) > 0 else e
        for e in spec.get("events") or []
    ]
    condition = spec.get("condition_at")
    return {
        **spec,
        "events": events,
        "condition_at": None if condition is None else condition + by,
        **(
            {}
            if spec.get("condition_until") is None
            else {"condition_until": spec["condition_until"] + by}
        ),
        "kill_at": float(spec["kill_at"]) + by,
        "event_timeline_end": float(spec["event_timeline_end"]) + by,
    }


def deadline_s(spec: dict[str, Any], speed_factor: float, reaction_window: float) -> float:
    """Wall seconds after the run's start at which the agent is stopped (see module doc)."""
    return run_end(spec) / speed_factor + reaction_window


@dataclass(frozen=True)
class Task:
    scenario_id: str
    environment: str
    spec: dict[str, Any]
    folder: Path
    reference: str = ""  # how the server names it: the id, or the path for a repeated id
    trial: int = 1
    shift: float | None = None  # --jitter: `spec` is the scenario shifted by this many seconds
    authored: dict[str, Any] | None = None  # the scenario as the library has it, when shifted

    @property
    def category(self) -> str:
        return category_of(self.spec)

    @property
    def label(self) -> str:
        return self.scenario_id if self.trial == 1 else f"{self.scenario_id} (trial {self.trial})"


@dataclass
class Outcome:
    task: Task
    status: str  # passed, failed, error, skipped
    detail: str = ""
    wall_s: float = 0.0
    label: str = ""  # the control agent, when bench validate runs several
    output_tail: tuple[str, ...] = ()  # the agent's last output lines, shown when it did not pass


def discover(
    client: ControlClient,
    *,
    task: str | list[str] | None = None,
    filter: str | None = None,
    skipped: list[dict] | None = None,
) -> list[dict]:
    """The server's scenario library in path order, narrowed by --task (repeatable: an id or
    a file's path) and --filter. Files the server could not load are left out, and appended to
    `skipped` when given, so the caller can say why."""
    tasks = [task] if isinstance(task, str) else list(task or [])
    listing = []
    for entry in client.scenarios():
        if entry.get("id") is None:  # a file that failed validation: reported, not run
            if skipped is not None:
                skipped.append(entry)
            continue
        listing.append(entry)
    selected = [s for s in listing if not tasks or s["id"] in tasks or s.get("path") in tasks]
    for wanted in tasks:
        if not any(wanted in (s["id"], s.get("path")) for s in selected):
            raise BenchError(f"No scenario found with id {wanted!r}")
    if filter:
        selected = [s for s in selected if filter.lower() in s["id"].lower()]
        if not selected:
            raise BenchError(f"No scenario id contains {filter!r}")
    return selected


@dataclass
class Harness:
    """Everything tasks share: config, client, where results go, which agent to launch."""

    config: BenchConfig
    client: ControlClient
    results_root: Path  # results/<NAME>
    base_dir: Path
    agent: str | None = None  # a control agent instead of the config's agent_subprocess
    retry_errors: bool = False
    # "virtual": runs on a virtual clock that the (scripted control) agent jumps through
    # /advance instead of waiting; "live": the clock moves with the wall, as for a real agent;
    # "fast_forward": live, and the agent's declared waits (its wait URL) skip ahead.
    clock: str = "live"
    private_paths: tuple[Path, ...] = ()  # more folders of the project: the scenario library
    stopping: threading.Event = field(default_factory=threading.Event)
    _live: set = field(default_factory=set)
    _lock: threading.Lock = field(default_factory=threading.Lock)

    @property
    def speed_factor(self) -> float:
        return self.config.speed_factor

    @property
    def project_paths(self) -> tuple[Path, ...]:
        """Folders no value of the agent's environment may name: the project, its Python, the
        results and the scenario library (the answer key)."""
        return (self.base_dir, *project_python(), self.results_root, *self.private_paths)

    def builtin(self, module: str, *, stdlib_only: bool = False) -> list[str]:
        """The command running a built-in agent, a module of this project: the folder holding
        its code goes on its import path through its command line, never through its
        environment. An agent of the standard library only starts without `site` (`-S`): a
        validation starts one per scenario and control agent, and the virtualenv's path hooks
        were most of each start's CPU."""
        flags = ["-S"] if stdlib_only else []
        return [sys.executable, *flags, "-c", LAUNCH_MODULE, str(CODE_DIR), module]

    def tasks(self, listing: list[dict], trials: int = 1) -> list[Task]:
        tasks = []
        for entry in listing:
            # A file repeating another's id runs by its path, its results under its file name.
            reference = entry.get("path") if entry.get("duplicate_of") else entry["id"]
            spec = self.client.scenario(reference)
            name = Path(reference).stem if entry.get("duplicate_of") else spec["id"]
            folder = self.results_root / spec["environment"] / name
            for n in range(1, trials + 1):
                task = Task(
                    spec["id"], spec["environment"], spec, trial_folder(folder, n), reference, n
                )
                if self.config.jitter > 0:
                    by = timeline_shift(spec, self.config.jitter, self.config.seed, n)
                    task = dataclasses.replace(
                        task, spec=shifted(spec, by), shift=by, authored=spec
                    )
                tasks.append(task)
        return tasks

    def should_skip(
        self,
        task: Task,
        records: ledger.Records | None = None,
        say: Callable[[str], None] | None = None,
    ) -> str | None:
        """Why the task is not run again (None: it is run). A results.json the set's ledger
        (`records`, read now if not given) does not have as written is no verdict: it is set
        aside as results.json.unverified, `say` is told in one line and the task runs again."""
        results = task.folder / RESULTS
        if results.exists():
            if records is None:
                records = ledger.Records.of(self.results_root)
            if records.vouches(results):
                return "already done" + self._speed_note(task)
            results.replace(results.with_name(UNVERIFIED))
            if say is not None:
                say(
                    f"Running {task.label} again: {results} was not written by the harness "
                    f"(no match in {LEDGER}; kept as {UNVERIFIED})"
                )
        if (task.folder / ERROR).exists():
            if not self.retry_errors:
                return (
                    f"previous error: {error_cause_of(task.folder)}; --retry-errors runs it again"
                )
            (task.folder / ERROR).unlink()
        return None

    def _speed_note(self, task: Task) -> str:
        """A resumed benchmark mixes speeds if the factor changed: say so rather than hide it."""
        try:
            recorded = json.loads((task.folder / RESULTS).read_text()).get("speed_factor")
        except (OSError, ValueError):
            return ""
        if recorded is None or float(recorded) == float(self.speed_factor):
            return ""
        return (
            f" at speed {recorded:g}, not {self.speed_factor:g}: use a new NAME to compare speeds"
        )

    def command_for(
        self, task: Task, run: dict[str, Any], prompt: str, workspace: AgentWorkspace | None = None
    ) -> tuple[list[str] | str, bool, dict]:
        """The agent's command line, whether it is a shell line, and its environment; it runs
        in `workspace` (default: the task's folder), which its task-folder placeholders name."""
        where = (workspace.path if workspace else task.folder).resolve()
        env = agent_environment(os.environ, self.project_paths)
        env["PWD"] = str(where)
        if self.agent or self.config.reference_agent:
            env["PYTHONUNBUFFERED"] = "1"  # output.txt shows each step as it happens
        if self.config.reference_agent:
            return self._reference_command(task, run, where), False, env
        if self.agent:
            condition = task.spec.get("condition_at")
            argv = [
                *self.builtin("apps.bench.agents", stdlib_only=True),
                self.agent,
                "--task-url",
                run["task_url"],
                "--contact-url",
                run["contact_url"],
                "--speed-factor",
                repr(self.speed_factor),
                "--condition-at",
                "none" if condition is None else repr(float(condition)),
                "--solution",
                json.dumps(self.solution_for(task)),
                "--deadline",
                repr(deadline_s(task.spec, self.speed_factor, self.config.reaction_window)),
            ]
            if task.spec.get("condition_until") is not None:
                argv += ["--condition-until", repr(float(task.spec["condition_until"]))]
            if self.agent == "fixed_time":
                argv += ["--contact-at", repr(min(FIXED_CONTACT_AT, run_end(task.spec) / 2))]
            if self.clock == "virtual":
                argv += [
                    "--advance-url",
                    f"{self.client.base_url}/api/runs/{run['id']}/advance/",
                    "--timeline-end",
                    repr(float(task.spec["event_timeline_end"])),
                ]
                if self.client.token:
                    env["SENTINEL_CONTROL_TOKEN"] = self.client.token
            return argv, False, env
        values = {
            "__TASK_URL__": run["task_url"],
            "__CONTACT_URL__": run["contact_url"],
            "__WAIT_URL__": run["wait_url"],
            "__TASK_PROMPT__": prompt,
            "__BASE_DIR__": str(self.base_dir),
            "__TASK_DIR__": str(where),
            "__PYTHON__": sys.executable,
        }
        # `python` in the agent's command is the project's Python (the .venv's, with its
        # packages), not whichever one the system has first on PATH: the workspace's shims.
        if workspace is not None:
            env["PATH"] = os.pathsep.join(filter(None, [str(workspace.shims()), env["PATH"]]))
        env["SENTINEL_TASK_DIR"] = str(where)
        command, shell = self.config.agent_command(values)
        return command, shell, env

    def solution_for(self, task: Task) -> list[dict]:
        """The steps a control agent performs: the scenario's solution, or for act_all that
        solution on every item there is when it acts (just before the deadline)."""
        solution = task.spec.get("solution") or []
        if self.agent != "act_all":
            return solution
        limit = deadline_s(task.spec, self.speed_factor, self.config.reaction_window)
        acts_at = (limit - SLEEPER_MARGIN_S) * self.speed_factor
        return every_item_steps(task.spec, min(acts_at, float(task.spec["event_timeline_end"])))

    def _reference_command(self, task: Task, run: dict[str, Any], where: Path) -> list[str]:
        """A built-in reference agent: the project's Python, the task's URLs and its prompt file.

        Its wall budget defaults to the task's deadline, so it stops by itself (leaving its
        costs and transcript complete) rather than being killed mid-call.
        """
        agent = self.config.reference_agent
        argv = [*self.builtin("apps.browser_agent"), *agent.arguments()]
        argv += ["--task-url", run["task_url"], "--contact-url", run["contact_url"]]
        if self.clock == "fast_forward":
            argv += ["--wait-url", run["wait_url"]]
        argv += ["--prompt-file", str(where / "prompt.txt")]
        # Not the speed factor: like the paper's agents, it knows only its URLs and prompt and
        # lives in wall time, so a faster scenario leaves it less time to notice.
        argv += ["--task-dir", str(where)]
        if agent.max_wall is None:
            limit = deadline_s(task.spec, self.speed_factor, self.config.reaction_window)
            argv += ["--max-wall", repr(limit)]
        return argv

    # --- one task --------------------------------------------------------------------------

    def run_task(self, task: Task) -> Outcome:
        began = time.monotonic()
        task.folder.mkdir(parents=True, exist_ok=True)
        try:
            result = self._run_task(task)
            cause = result.pop("error_cause", None)
        except Interrupted:
            return Outcome(task, "error", "interrupted", time.monotonic() - began)
        except Exception as exc:  # any failure here is the harness's, reported as such
            kind = (
                "harness error"
                if isinstance(exc, HarnessError)
                else f"harness error ({type(exc).__name__})"
            )
            (task.folder / ERROR).write_text(
                f"{kind}: {exc}\n\n{traceback.format_exc()}", encoding="utf-8"
            )
            return Outcome(
                task,
                "error",
                str(exc),
                time.monotonic() - began,
                output_tail=output_tail(task.folder / OUTPUT),
            )
        if cause:
            # Not the agent's doing: kept apart in error.txt (its cause first), never a result.
            (task.folder / ERROR).write_text(
                f"{cause}\n\nverdict (not counted): {json.dumps(result, default=str)}\n",
                encoding="utf-8",
            )
            return Outcome(
                task,
                "error",
                cause,
                time.monotonic() - began,
                output_tail=output_tail(task.folder / OUTPUT),
            )
        status = graded_outcome(result)
        return Outcome(
            task,
            status,
            result.get("detail", ""),
            time.monotonic() - began,
            output_tail=() if status == "passed" else output_tail(task.folder / OUTPUT),
        )

    def _run_task(self, task: Task) -> dict[str, Any]:
        sf = self.speed_factor
        # A shifted scenario is played as sent; the others by their name in the library.
        scenario = task.spec if task.shift is not None else task.reference or task.scenario_id
        run = self.client.create_run(scenario, sf, clock_mode=self.clock)
        prompt = augment_prompt(
            run.get("prompt") or task.spec.get("prompt", ""), run["contact_url"]
        )
        (task.folder / PROMPT).write_text(prompt, encoding="utf-8")
        limit = deadline_s(task.spec, sf, self.config.reaction_window)
        ledger.start(self.results_root)  # (bench run started it; bench validate's sets here)
        launched = time.monotonic()
        # The agent works in a fresh folder of its own, outside the project and the results:
        # it can never write a result of its own (a forged results.json was taken as done).
        with AgentWorkspace(task.folder) as workspace:
            workspace.place(PROMPT, prompt)
            command, shell, env = self.command_for(task, run, prompt, workspace)
            try:
                process = subprocess.Popen(
                    reaper_command(command, shell, task.folder / OUTPUT),
                    cwd=workspace.path,
                    env=env,
                    stdin=subprocess.DEVNULL,
                    stdout=subprocess.PIPE,
                    start_new_session=True,
                )
            except OSError as exc:
                raise HarnessError(f"could not launch the agent {command!r}: {exc}") from exc
            agent_group = agent_pid_of(process)
            with self._lock:
                self._live.add(process.pid)
            try:
                killed = self._supervise(process, run["id"], limit, launched)
                left_at = None if killed else self._clock_reading(run["id"])
            finally:
                stop_agent(process, agent_group)
                with self._lock:
                    self._live.discard(process.pid)
        if self.stopping.is_set():
            with contextlib.suppress(HarnessError):
                self.client.close_run(run["id"])
            raise Interrupted(task.scenario_id)
        verdict = self.client.evaluate(run["id"])
        with contextlib.suppress(HarnessError):
            self.client.close_run(run["id"])
        # Exported once closed, so the log it saves (and the verdict it records for `replay`)
        # is the run's last: a header line, then every event.
        exported = self.client.export(run["id"])
        with open(task.folder / EVENTS, "w", encoding="utf-8") as log:
            for line in exported:
                log.write(json.dumps(line, default=str) + "\n")
        result = {
            **verdict,
            "scenario_id": task.scenario_id,
            "environment": task.environment,
            "category": task.category,
            **axes_of(task.spec),
            "speed_factor": sf,
            "clock": self.clock,
            "deadline_s": limit,
            "agent_exit_code": process.returncode,
            "agent_killed": killed,
            "agent_left_at": left_at,  # the run's clock (wall s) when it exited by itself
            "agent_wall_s": round(time.monotonic() - launched, 3),
            "noop_rule": self.config.noop_rule,
        }
        if workspace.refused:  # what the agent left that was not kept, and why
            result["agent_files_refused"] = workspace.refused
        # (A clock stops at its timeline's end: an agent cannot outstay that.)
        end = min(run_end(task.spec), float(task.spec.get("event_timeline_end") or math.inf))
        result = noop_rule_applied(result, self.config.noop_rule, end / sf)
        if task.trial != 1:
            result["trial"] = task.trial
        if task.shift is not None:
            result["timeline_shift"] = task.shift
        if task.spec.get("contact_rubric"):  # what `bench grade` judges the report against
            result["contact_rubric"] = task.spec["contact_rubric"]
            result["prompt"] = task.spec.get("prompt", "")
        header = exported[0] if exported and "format" in exported[0] else {}
        result["catalog_hash"] = (header.get("run") or {}).get("catalog_hash")
        cause = error_cause(verdict, process.returncode, killed)
        if killed and self.clock == "virtual" and not cause:
            # No deadline exists on a virtual clock: a kill by the guard is a machine too slow
            # (or an agent hung), never a verdict on the scenario.
            cause = "the agent outlived its wall-time guard on a virtual clock (a loaded machine?)"
        if cause:
            return {**result, "error_cause": cause}
        ledger.write_result(self.results_root, task.folder / RESULTS, result)
        return result

    def _clock_reading(self, run_id: int) -> float | None:
        """The run's clock now, in wall seconds (None if the server could not say)."""
        with contextlib.suppress(HarnessError, KeyError, TypeError, ValueError):
            return float(self.client.run(run_id, retries=1)["sim_time"]) / self.speed_factor
        return None

    def _supervise(
        self, process: subprocess.Popen, run_id: int, limit: float, launched: float
    ) -> bool:
        """Wait for the agent or its deadline; True when it had to be killed."""
        # A virtual clock never starts; its agent moves it, so the limit is only a guard
        # against a hung agent, counted from launch and generous: on a loaded machine a
        # control agent may take many wall seconds to jump through its run. A fast-forward
        # clock is read all along: every skip brings the deadline (the same simulated moment
        # as on a live clock) sooner in wall time.
        virtual = self.clock == "virtual"
        deadline = launched + (
            max(VIRTUAL_GUARD_FACTOR * limit, VIRTUAL_GUARD_MIN_S) if virtual else limit
        )
        started = virtual
        next_poll = launched
        while process.poll() is None:
            now = time.monotonic()
            if self.stopping.is_set():
                return True
            if (not started or self.clock == "fast_forward") and now >= next_poll:
                next_poll = now + START_POLL_S
                with contextlib.suppress(HarnessError, KeyError, TypeError):
                    info = self.client.run(run_id, retries=1)
                    # (A frozen clock, once completed, no longer moves the deadline.)
                    if info["status"] != "ready" and not (
                        started and info["status"] != "running_auto"
                    ):
                        started = True
                        deadline = (
                            time.monotonic() - float(info["sim_time"]) / self.speed_factor + limit
                        )
            if now >= deadline:
                status = None
                with contextlib.suppress(HarnessError, KeyError, TypeError):
                    status = self.client.run(run_id, retries=1)["status"]
                if status == "completed" and self.config.grace > 0:
                    with contextlib.suppress(subprocess.TimeoutExpired):
                        process.wait(timeout=self.config.grace)
                return process.poll() is None
            time.sleep(0.1)
        return False

    def kill_all(self) -> None:
        self.stopping.set()
        with self._lock:
            pids = list(self._live)
        for pid in pids:  # each reaper kills its agent and all under it, then exits
            with contextlib.suppress(ProcessLookupError, PermissionError):
                os.kill(pid, signal.SIGTERM)

    # --- many tasks --------------------------------------------------------------------------

    def pending(self, tasks: list[Task], progress: Progress) -> list[Task]:
        """The tasks still to run; the others are reported as skipped (resumability)."""
        adopted = ledger.start(self.results_root)
        if adopted:
            progress.line(
                f"{self.results_root / LEDGER}: started, with the {adopted} results.json "
                "written before it"
            )
        records = ledger.Records.of(self.results_root)
        todo = []
        for task in tasks:
            reason = self.should_skip(task, records, progress.line)
            if reason:
                progress.line(f"Skipping {task.label} ({reason})")
            else:
                todo.append(task)
        return todo

    def tracked(self, task: Task, progress: Progress) -> Outcome:
        if self.stopping.is_set():
            return Outcome(task, "error", "interrupted")
        label = f"[{self.agent}] " if self.agent else ""
        progress.started(task, label)
        outcome = self.run_task(task)
        outcome.label = label
        return outcome


def run_pool(jobs: list[tuple[Harness, Task]], parallel: int, progress: Progress) -> list[Outcome]:
    """Run (harness, task) jobs on a thread pool; on any interruption kill every agent."""
    outcomes: list[Outcome] = []
    progress.begin(len(jobs))
    pool = ThreadPoolExecutor(max_workers=max(1, parallel))
    try:
        futures = [pool.submit(harness.tracked, task, progress) for harness, task in jobs]
        for future in as_completed(futures):
            outcome = future.result()
            outcomes.append(outcome)
            progress.finished(outcome)
    except BaseException:
        # Ctrl-C (or a bug): stop supervising, kill every agent group, and leave the
        # interrupted tasks without results so that the next run does them again.
        for harness in {id(h): h for h, _ in jobs}.values():
            harness.kill_all()
        raise
    finally:
        pool.shutdown(wait=True, cancel_futures=True)
        progress.end()
    return outcomes


def output_tail(path: Path, lines: int = OUTPUT_TAIL_LINES) -> tuple[str, ...]:
    """The last non-empty lines of an agent's output.txt: why it failed, shown in the console."""
    try:
        with open(path, "rb") as fh:
            fh.seek(0, os.SEEK_END)
            fh.seek(max(0, fh.tell() - 8192))
            text = fh.read().decode("utf-8", errors="replace")
    except OSError:
        return ()
    return tuple(line for line in text.splitlines() if line.strip())[-lines:]


REAPER = Path(__file__).with_name("reaper.py")
OUTPUT_CAP = 16 * 1024 * 1024  # of output.txt: the first and last 8 MiB are kept
REAPER_STOP_S = 15.0


def reaper_command(command: list[str] | str, shell: bool, output: Path) -> list[str]:
    """The agent's command run under apps/bench/reaper.py (by path, and without `site`: the
    standard library only)."""
    argv = [
        sys.executable,
        "-S",
        str(REAPER),
        "--output",
        str(output.resolve()),
        "--cap",
        str(OUTPUT_CAP),
    ]
    argv += ["--shell", "--", command] if shell else ["--", *command]
    return argv


def agent_pid_of(process: subprocess.Popen) -> int | None:
    """The agent's pid (its process group), from the reaper's first line; None if it never
    launched one."""
    assert process.stdout is not None
    words = process.stdout.readline().split()
    return int(words[1]) if len(words) == 2 and words[0] == b"agent" else None


def stop_agent(process: subprocess.Popen, agent_group: int | None) -> None:
    """Stop the agent, its children and whatever it left running (the reaper does it), then,
    should the reaper not have managed, SIGKILL both process groups."""
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.kill(process.pid, signal.SIGTERM)
    with contextlib.suppress(subprocess.TimeoutExpired):
        process.wait(timeout=REAPER_STOP_S)
    for group in (process.pid, agent_group):
        if group is not None:
            with contextlib.suppress(ProcessLookupError, PermissionError):
                os.killpg(group, signal.SIGKILL)
    with contextlib.suppress(subprocess.TimeoutExpired):
        process.wait(timeout=10)
    if process.stdout is not None:
        process.stdout.close()


# The folder holding the `apps` package: a checkout's top, or an installed package's
# site-packages (where the base folder is the package's resources, with no code).
CODE_DIR = Path(__file__).resolve().parents[2]
# Runs a module whose folder is given on the command line (`-c CODE FOLDER MODULE ARGS…`).
LAUNCH_MODULE = (
    "import runpy, sys; sys.path.insert(0, sys.argv.pop(1)); "
    "runpy.run_module(sys.argv.pop(1), run_name='__main__', alter_sys=True)"
)
# Variables naming the harness's own setup, whatever their value: the agent has no use for them,
# and some name the project without a path (DJANGO_SETTINGS_MODULE) or a secret (the control
# token of a server given by SENTINEL_CONTROL_TOKEN).
PROJECT_VARIABLES = frozenset(
    {"PWD", "OLDPWD", "VIRTUAL_ENV", "VIRTUAL_ENV_PROMPT", "PYTHONPATH", "PYTHONHOME"}
    | {"PYTHONSTARTUP", "PYTHONSAFEPATH", "PYTHONUSERBASE", "CONDA_PREFIX"}
)
PROJECT_PREFIXES = ("SENTINEL_", "DJANGO_", "PYTEST_", "COV_CORE_")
PYTHON_NAMES = ("python", "python3")  # what the agent's PATH runs as the project's Python


def project_python() -> tuple[Path, ...]:
    """The project's Python when it is a virtualenv of its own; a system Python's prefix
    (`/usr`) is the machine's, which the agent needs."""
    return (Path(sys.prefix),) if sys.prefix != sys.base_prefix else ()


def path_names(paths: tuple[Path, ...] | list[Path]) -> tuple[str, ...]:
    """Every spelling of `paths` a value could carry: as given and with links resolved."""
    names = {str(p.absolute()) for p in paths} | {str(p.resolve()) for p in paths}
    return tuple(sorted(n for n in names if n != os.sep))


def without_project(search_path: str, names: tuple[str, ...]) -> str:
    """A PATH-like value less its entries inside the project."""
    inside = tuple(n + os.sep for n in names)
    kept = [
        e
        for e in search_path.split(os.pathsep)
        if e and e not in names and not e.startswith(inside)
    ]
    return os.pathsep.join(kept)


def agent_environment(environ: Mapping[str, str], project: tuple[Path, ...]) -> dict[str, str]:
    """The harness's environment less every trace of the project, for an agent: its variables
    (PROJECT_VARIABLES, PROJECT_PREFIXES), PATH entries inside it, and any other variable whose
    value names one of its folders. What an agent needs of the machine (HOME, a model's API
    key, proxies, locale) passes. An agent that looks can still find the project (its own
    command line names the Python it runs), so this is hygiene, not a sandbox: nothing hands
    the agent the way to the answer key (README, "What an agent can reach")."""
    names = path_names(project)
    env = {}
    for name, value in environ.items():
        if name in PROJECT_VARIABLES or name.startswith(PROJECT_PREFIXES):
            continue
        if name == "PATH":
            value = without_project(value, names)
        elif any(n in value for n in names):
            continue
        env[name] = value
    env.setdefault("PATH", "")
    return env


REFUSED_KEPT = 50  # refused files named in results.json (`agent_files_refused`), at most
# What one trial's agent may leave to be copied back: a long run's screenshots and transcript
# are tens of MiB, so these only stop an agent (or a runaway loop) from filling the results'
# disk. Folders are walked top-down, so the top-level files the reports read come first.
AGENT_FILES_MAX_BYTES = 512 * 1024 * 1024
AGENT_FILES_MAX_COUNT = 20_000
TRIAL_NAME = re.compile(re.escape(TRIAL_PREFIX) + r"[0-9]+")


def refusal(relative: Path) -> str | None:
    """Why a path the agent left in its folder is not copied back (None: it is)."""
    if relative.is_absolute() or not relative.parts:
        return "not inside the agent's folder"
    if any(part in ("", ".", "..") for part in relative.parts):
        return "not inside the agent's folder"
    if any(part in HARNESS_NAMES or TRIAL_NAME.fullmatch(part) for part in relative.parts):
        return "a name of the harness's"
    return None


def _not_a_folder(name: str, dir_fd: int) -> str | None:
    """Why a sub-folder the agent left is not walked into (None: it is a folder)."""
    try:
        mode = os.stat(name, dir_fd=dir_fd, follow_symlinks=False).st_mode
    except OSError:
        return "unreadable"
    return None if stat.S_ISDIR(mode) else "a symbolic link"


class AgentWorkspace:
    """A fresh temporary folder for one agent; what the agent leaves there (its costs.json,
    transcript, screenshots) is copied afterwards into `agent/` in the trial's result folder.

    Why a folder of its own rather than the trial's folder itself: that folder is the
    harness's — results.json, error.txt, output.txt, events.jsonl, prompt.txt, and (trial 1's)
    the folders of the task's other trials, trial-2/… An agent once wrote `trial-2/results.json`
    in its own folder, had it copied beside its trial's, and a later `bench run --trials 2`
    took it for trial 2's verdict. Copied under `agent/`, nothing of the agent's can land where
    the harness reads or writes a record, whatever it names it. As well, a file is copied only
    when it is a regular file reached without a symbolic link (opened relative to its folder,
    O_NOFOLLOW, so a link swapped in meanwhile is refused too) and none of its path is a name
    of the harness's (layout.HARNESS_NAMES) or of a trial's folder, at any depth: such a file
    is a forgery or a mistake, and never what the reports read from `agent/`. What was refused
    is listed in results.json (`agent_files_refused`)."""

    def __init__(self, results: Path):
        self.results = results
        self.refused: list[str] = []
        self.placed: set[Path] = set()  # the harness's files in the agent's folder: not copied
        self.room = Allowance(AGENT_FILES_MAX_BYTES, AGENT_FILES_MAX_COUNT)
        # The agent's folder is `task` inside a folder of its own, beside its PATH's shims.
        self.root = Path(tempfile.mkdtemp(prefix="sentinel-agent-")).resolve()
        self.path = self.root / "task"
        self.path.mkdir()

    def __enter__(self) -> AgentWorkspace:
        return self

    def place(self, name: str, text: str) -> None:
        """A file of the harness's for the agent to read (its prompt.txt): never copied back."""
        (self.path / name).write_text(text, encoding="utf-8")
        self.placed.add(Path(name))

    def shims(self) -> Path:
        """A folder beside the workspace where `python` and `python3` run the project's Python
        by its absolute path: a link would not do (a virtualenv's Python finds its packages from
        the path it was started by), and the project's own folder on PATH would name it."""
        shims = self.root / "bin"
        shims.mkdir(exist_ok=True)
        for name in PYTHON_NAMES:
            shim = shims / name
            shim.write_text(
                f'#!/bin/sh\nexec {shlex.quote(sys.executable)} "$@"\n', encoding="utf-8"
            )
            shim.chmod(0o755)
        return shims

    def __exit__(self, *exc) -> None:
        try:
            self.copy_back()
        finally:
            shutil.rmtree(self.root, ignore_errors=True)

    def _refuse(self, relative: Path, why: str) -> None:
        if len(self.refused) < REFUSED_KEPT:
            self.refused.append(f"{relative.as_posix()}: {why}")

    def copy_back(self) -> Path:
        """Copy the agent's files into `<trial folder>/agent/` (an earlier attempt's replaced:
        a task run again keeps only its last agent's); returns that folder."""
        target = self.results / AGENT
        if target.is_symlink() or target.is_file():
            target.unlink()
        shutil.rmtree(target, ignore_errors=True)
        target.mkdir(parents=True)
        # fwalk: each folder is opened without following a link, and files are opened
        # relative to it, so no path the agent can change is followed between check and copy.
        for folder, dirnames, filenames, dir_fd in os.fwalk(self.path):
            where = Path(folder).relative_to(self.path)
            for name in sorted(dirnames):
                why = refusal(where / name) or _not_a_folder(name, dir_fd)
                if why is not None:
                    dirnames.remove(name)
                    self._refuse(where / name, why)
            for name in sorted(filenames):
                relative = where / name
                if relative in self.placed:
                    continue
                why = refusal(relative) or self._copy(name, dir_fd, target / relative)
                if why is not None:
                    self._refuse(relative, why)
        return target

    def _copy(self, name: str, dir_fd: int, to: Path) -> str | None:
        """Copy one regular file, opened in its folder without following a link, if the trial's
        allowance has room for it; None when copied, else why not."""
        try:
            fd = os.open(name, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK, dir_fd=dir_fd)
        except OSError:
            return "a symbolic link or unreadable"
        with os.fdopen(fd, "rb") as source:
            info = os.fstat(source.fileno())
            if not stat.S_ISREG(info.st_mode):
                return "not a regular file"
            why = self.room.take(info.st_size)
            if why is not None:
                return why
            to.parent.mkdir(parents=True, exist_ok=True)
            with open(to, "xb") as copy:
                # The size taken, not more: a file that grows meanwhile is cut where it was seen.
                left = info.st_size
                while left and (chunk := source.read(min(left, 1 << 20))):
                    copy.write(chunk)
                    left -= len(chunk)
        os.utime(to, ns=(info.st_atime_ns, info.st_mtime_ns))
        return None


class Allowance:
    """How many bytes and files one trial's agent may still have copied back."""

    def __init__(self, max_bytes: int, max_count: int):
        self.max_bytes, self.max_count = max_bytes, max_count
        self.bytes = self.count = 0

    def take(self, size: int) -> str | None:
        """Room for one more file of `size` bytes (None), or why there is none."""
        if self.count >= self.max_count:
            return f"over the {self.max_count:,} files copied back per trial"
        if self.bytes + size > self.max_bytes:
            return f"over the {self.max_bytes // 2**20:,} MiB copied back per trial"
        self.bytes += size
        self.count += 1
        return None


def write_json_atomically(path: Path, data: Any) -> None:
    tmp = path.with_suffix(path.suffix + ".tmp")
    tmp.write_text(json.dumps(data, indent=2, default=str) + "\n", encoding="utf-8")
    tmp.replace(path)


class Progress:
    """A one-line bar (done, running, passed) on a TTY; plain lines otherwise."""

    def __init__(self, stream: TextIO, *, tty: bool | None = None, label: str = ""):
        self.stream = stream
        self.tty = stream.isatty() if tty is None else tty
        self.label = label
        self.total = self.done = self.running = self.passed = self.errors = 0
        self._lock = threading.Lock()
        self._began = time.monotonic()

    def _write(self, text: str) -> None:
        self.stream.write(text)
        self.stream.flush()

    def line(self, text: str) -> None:
        with self._lock:
            if self.tty:
                self._write("\r\033[K" + text + "\n")
                self._bar()
            else:
                self._write(text + "\n")

    def _bar(self) -> None:
        if not self.tty or not self.total:
            return
        width = 30
        filled = int(width * self.done / self.total)
        elapsed = time.monotonic() - self._began
        self._write(
            f"\r\033[K{self.label}[{'#' * filled}{'.' * (width - filled)}] done {self.done}/{self.total} "
            f"running {self.running} passed {self.passed} errors {self.errors}  {elapsed:5.0f}s"
        )

    def begin(self, total: int) -> None:
        with self._lock:
            self.total, self._began = total, time.monotonic()
            self._bar()

    def started(self, task: Task, label: str = "") -> None:
        with self._lock:
            self.running += 1
            if self.tty:
                self._bar()
            else:
                self._write(f"  Running {label}{task.label} ...\n")

    def finished(self, outcome: Outcome) -> None:
        with self._lock:
            self.running -= 1
            self.done += 1
            self.passed += outcome.status == "passed"
            self.errors += outcome.status == "error"
            extra = f": {outcome.detail}" if outcome.status != "passed" and outcome.detail else ""
            reason = "".join(
                f"      {outcome.task.folder / OUTPUT}: {line}\n" for line in outcome.output_tail
            )
            if self.tty:
                if outcome.status != "passed":
                    self._write(
                        f"\r\033[K  {outcome.status.upper()} {outcome.label}"
                        f"{outcome.task.label}{extra}\n{reason}"
                    )
                self._bar()
            else:
                self._write(
                    f"  {outcome.status.upper()} {outcome.label}{outcome.task.label} ({outcome.wall_s:.1f}s){extra} "
                    f"[done {self.done}/{self.total}, running {self.running}, passed {self.passed}]\n"
                    + reason
                )

    def end(self) -> None:
        with self._lock:
            if self.tty and self.total:
                self._write("\n")
