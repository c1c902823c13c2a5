"""`manage.py bench run | grade | validate` — the benchmark harness (docs: apps/bench/README.md)."""

from __future__ import annotations

import contextlib
import dataclasses
import os
import secrets
import signal
import tempfile
import threading
import time
from datetime import datetime
from pathlib import Path

from django.conf import settings
from django.core.management import call_command
from django.core.management.base import BaseCommand, CommandError
from django.db import connection
from django.db.migrations.executor import MigrationExecutor
from django.test.utils import override_settings
from django.utils import timezone

from apps.bench import preflight
from apps.bench.cheating import cheating_problems
from apps.bench.client import ControlClient, HarnessError
from apps.bench.config import (
    BENCH_CLOCKS,
    REFERENCE_KINDS,
    BenchConfig,
    ConfigError,
    ReferenceAgent,
    bench_clock,
    load_config,
)
from apps.bench.grading import (
    TaskError,
    error_lines,
    load_rows,
    outcome_counts,
    summarise,
    task_errors,
)
from apps.bench.layout import ERROR, BenchError
from apps.bench.manifest import (
    build_manifest,
    git_commit,
    machine,
    project_version,
    read_manifest,
    scenario_hash,
    write_manifest,
)
from apps.bench.outcomes import NOOP_RULES
from apps.bench.runner import (
    CHEATING_AGENTS,
    CONTROL_AGENTS,
    WINDOW_AGENTS,
    Harness,
    Progress,
    Task,
    discover,
    run_pool,
)
from apps.bench.summary import build_summary, write_set_summary, write_summary
from apps.scenarios.library import library, scenario_root
from apps.scenarios.watching import WatchCheck, unseen_triggers
from events.timing import (
    MAX_CONDITION_AT,
    REACTION_WINDOW,
    SpeedFactorError,
    validate_speed_factor,
)
from sentinel_site.site_server import ServerDidNotStart, site_server

DEFAULT_CONFIG = "eval_config.yaml"
VALIDATE_RETRIES = 2  # times bench validate runs a task again after an error


@contextlib.contextmanager
def terminate_as_interrupt():
    """SIGTERM unwinds like Ctrl-C, so agents (in their own sessions) and the server are killed."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def interrupt(signum, frame):
        raise KeyboardInterrupt(f"signal {signum}")

    previous = signal.signal(signal.SIGTERM, interrupt)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def _usage(message: str) -> CommandError:
    return CommandError(message, returncode=2)


def _preflight_failed(problems: list[str]) -> CommandError:
    """Every problem on its own line; nothing was run."""
    return _usage("\n".join(f"preflight: {problem}" for problem in problems))


def config_as_used(cfg: BenchConfig, agent: str | None, trials: int) -> dict:
    """The configuration a result set was produced with: the file's keys, the command line's
    overrides applied, the control token left out."""
    used = {k: v for k, v in cfg.raw.items() if k != "control_token"}
    used.update(
        speed_factor=cfg.speed_factor,
        parallel=cfg.parallel,
        reaction_window=cfg.reaction_window,
        grace=cfg.grace,
        trials=trials,
        noop_rule=cfg.noop_rule,
    )
    if cfg.jitter > 0:
        used.update(jitter=cfg.jitter, seed=cfg.seed)
    if cfg.awake:  # the embedded server paced its fast-forward agents
        used["awake"] = cfg.awake
    if cfg.server_url:
        used["server_url"] = cfg.server_url
    if agent:
        used["control_agent"] = agent
        used.pop("agent_subprocess", None)
    if cfg.reference_agent:
        used["agent"] = dataclasses.asdict(cfg.reference_agent)
        used.pop("agent_subprocess", None)
    return used


def update_manifest(
    name: str,
    run_dir: Path,
    used: dict,
    tasks: list[Task],
    started_at: datetime,
    base_dir: Path,
    errors: list[TaskError],
) -> None:
    """`manifest.json` after this `bench run`: what produced the set, and its counts now."""
    rows = load_rows(run_dir) if run_dir.is_dir() else []
    write_manifest(
        run_dir,
        build_manifest(
            read_manifest(run_dir),
            name=name,
            config=used,
            version=project_version(base_dir),
            commit=git_commit(base_dir),
            scenarios={t.scenario_id: scenario_hash(t.authored or t.spec) for t in tasks},
            catalog_hashes=sorted(
                {str(r.result["catalog_hash"]) for r in rows if r.result.get("catalog_hash")}
            ),
            started_at=started_at,
            finished_at=timezone.now(),
            counts=outcome_counts(rows, errors),
            host=machine(),
        ),
    )


def reference_changes(
    cfg: BenchConfig, agent: str | None, model: str | None, model_url: str | None
) -> dict:
    """Config changes that make `bench run` use a reference agent, from --agent/--model/--model-url.

    `--agent wait_for|sleep` picks the kind (the config's `agent:` gives the rest, or --model);
    --model and --model-url override the config's `agent:` alone.
    """
    if agent not in REFERENCE_KINDS and not (model or model_url):
        return {}
    if agent is not None and agent not in REFERENCE_KINDS:
        raise _usage(f"--model and --model-url are for the reference agents, not --agent {agent}")
    base = cfg.reference_agent
    kind = agent or (base.kind if base else None)
    if kind is None:
        raise _usage("--model/--model-url need --agent wait_for|sleep or an agent: in the config")
    chosen_model = model or (base.model if base else None)
    if not chosen_model:
        raise _usage(f"--agent {kind} needs a model: pass --model or set agent.model in the config")
    if model_url and not model_url.startswith(("http://", "https://")):
        raise _usage(f"--model-url must be an http:// or https:// URL, got {model_url!r}")
    reference = dataclasses.replace(
        base or ReferenceAgent(kind, chosen_model),
        kind=kind,
        model=chosen_model,
        base_url=(model_url.rstrip("/") if model_url else None) or (base and base.base_url),
    )
    return {"reference_agent": reference, "agent_subprocess": None}


def noop_rule(parser) -> None:
    parser.add_argument(
        "--noop-rule",
        choices=NOOP_RULES,
        default="paper",
        help="paper (default): a no-op passes only if the agent is still there when the run "
        "ends; original: any no-op without a contact passes, as the original harness counts",
    )


def scenario_folder(parser) -> None:
    parser.add_argument(
        "--scenarios",
        metavar="DIR",
        help="run this scenario folder (e.g. `manage.py generate`'s --out) instead of "
        "SENTINEL_SCENARIO_DIR",
    )


def use_scenario_folder(folder: str | None):
    """`--scenarios DIR`: the embedded server, the preflight and the checks read DIR (for this
    command only: the settings are restored after it)."""
    if folder is None:
        return contextlib.nullcontext()
    path = Path(folder).resolve()
    if not path.is_dir():
        raise _usage(f"--scenarios {folder}: no such folder")
    return override_settings(SENTINEL_SCENARIO_DIR=path)


class Command(BaseCommand):
    help = (
        "Benchmark harness: run an agent over the scenarios, grade the results, validate scenarios."
    )

    def add_arguments(self, parser):
        sub = parser.add_subparsers(
            dest="subcommand", required=True, metavar="{run,grade,validate,export-trajectories}"
        )

        run = sub.add_parser("run", help="run an agent on every selected scenario")
        run.add_argument("name", help="results go to <results-dir>/<name>/<env>/<scenario id>/")
        run.add_argument("--config", default=DEFAULT_CONFIG)
        run.add_argument("--parallel", type=int, help="tasks at once (config: parallel; default 1)")
        run.add_argument(
            "--task",
            action="append",
            help="exact scenario id, or a file's path (micromail/x.json); repeat for several",
        )
        run.add_argument("--filter", help="case-insensitive substring of the scenario id")
        scenario_folder(run)
        run.add_argument("--speed-factor", type=float)
        run.add_argument("--server-url", help="use this server instead of starting an embedded one")
        run.add_argument(
            "--agent",
            choices=CONTROL_AGENTS + CHEATING_AGENTS + REFERENCE_KINDS,
            help="a built-in agent instead of the config's: a control agent, or a reference "
            "agent (wait_for | sleep) on the config's agent.model or --model",
        )
        run.add_argument("--model", help="the reference agent's model (overrides agent.model)")
        run.add_argument(
            "--model-url",
            help="the reference agent's OpenAI-compatible base URL (overrides agent.base_url)",
        )
        run.add_argument(
            "--clock",
            choices=[*BENCH_CLOCKS, "fast-forward"],
            help="the runs' clock (config: clock; default live): fast-forward skips the clock "
            "when the agent declares a wait (its wait URL) instead of it sleeping",
        )
        run.add_argument(
            "--awake",
            type=int,
            metavar="N",
            help="fast-forward agents working at once on the embedded server, the others' waits "
            "held back while their clocks run (config: awake; default 0: no pacing). For agents "
            "whose work is this machine's (a scripted or local model): its cores",
        )
        run.add_argument(
            "--retry-errors", action="store_true", help="rerun tasks that have error.txt"
        )
        run.add_argument(
            "--trials",
            type=int,
            default=1,
            metavar="K",
            help="run every task K times, each its own run (trial n in <task>/trial-<n>/)",
        )
        run.add_argument("--results-dir", default="results")
        noop_rule(run)
        run.add_argument(
            "--jitter",
            type=float,
            default=0.0,
            metavar="SECONDS",
            help="shift each run's whole timeline by up to ±SECONDS (simulated), drawn per "
            "scenario and trial from --seed, so repeated trials do not share one trigger time",
        )
        run.add_argument("--seed", type=int, default=0, help="of the --jitter shifts (default 0)")

        grade = sub.add_parser(
            "grade", help="summarise a results tree, or compare several side by side"
        )
        grade.add_argument(
            "names", nargs="+", metavar="NAME", help="result sets under --results-dir"
        )
        grade.add_argument("--csv", action="store_true")
        grade.add_argument(
            "--html",
            metavar="PATH",
            help="also write a self-contained HTML report, transcript pages beside it",
        )
        grade.add_argument(
            "--timely-window",
            type=float,
            metavar="S",
            help="timely success: passed with reaction time <= S seconds "
            "(default: the config's reaction_window, 30)",
        )
        grade.add_argument(
            "--judge",
            metavar="MODEL",
            help="judge each report that has a contact_rubric with this model (else by the "
            "rubric's must_mention keywords)",
        )
        grade.add_argument(
            "--judge-url", help="the judge's OpenAI-compatible base URL (default: OpenAI's)"
        )
        grade.add_argument(
            "--judge-key-env",
            default="OPENAI_API_KEY",
            metavar="NAME",
            help="environment variable holding the judge's API key (default OPENAI_API_KEY)",
        )
        grade.add_argument("--task")
        grade.add_argument("--filter")
        grade.add_argument("--config", help=f"for prices (default: {DEFAULT_CONFIG} when present)")
        grade.add_argument("--results-dir", default="results")

        export = sub.add_parser(
            "export-trajectories",
            help="a result set as training data: one JSON object per task (README, "
            "'Trajectories for training')",
        )
        export.add_argument(
            "results",
            metavar="RESULTS",
            help="a result set's folder, or its name under --results-dir",
        )
        export.add_argument("--format", choices=["jsonl"], default="jsonl")
        export.add_argument("--out", metavar="FILE", help="default: standard output")
        export.add_argument("--results-dir", default="results")
        export.add_argument(
            "--timely-window", type=float, default=REACTION_WINDOW, metavar="S",
            help="the reward's timely: passed with reaction time <= S seconds (default 30)",
        )  # fmt: skip

        validate = sub.add_parser("validate", help="run the control agents on every scenario")
        validate.add_argument("--speed-factor", type=float, default=4.0)
        validate.add_argument(
            "--parallel", type=int, default=10, help="runs at once per control agent"
        )
        validate.add_argument("--filter")
        scenario_folder(validate)
        validate.add_argument("--server-url")
        validate.add_argument(
            "--reaction-window",
            type=float,
            default=REACTION_WINDOW,
            help="wall seconds after the last possible condition (default 30)",
        )
        validate.add_argument(
            "--keep", action="store_true", help="keep the temporary results folder"
        )
        noop_rule(validate)
        validate.add_argument(
            "--real-time",
            action="store_true",
            help="live clocks the agents wait on (default: virtual clocks they jump, in seconds)",
        )

    def handle(self, *args, subcommand: str, **options):
        try:
            with terminate_as_interrupt(), use_scenario_folder(options.pop("scenarios", None)):
                return getattr(self, f"handle_{subcommand.replace('-', '_')}")(**options)
        except (ConfigError, BenchError, SpeedFactorError) as exc:
            raise _usage(str(exc)) from None
        except HarnessError as exc:
            raise CommandError(f"harness error: {exc}") from None
        except KeyboardInterrupt:
            raise CommandError(
                "interrupted: every agent was killed; unfinished tasks run again next time",
                returncode=130,
            ) from None

    # --- shared ----------------------------------------------------------------------------

    @contextlib.contextmanager
    def server(
        self,
        server_url: str | None,
        token: str = "",
        *,
        external_is_preflight: bool = False,
        awake: int = 0,
    ):
        """The server to run against and its control token: `server_url` with `token` (or the
        configured one), else an embedded server of our own. That one runs with a fresh random
        control token and the flat endpoints off, so an agent's browser can reach nothing of the
        control side (no other run, no scenario, no /advance): only its own run's URLs."""
        if server_url:
            if external_is_preflight:
                problem = preflight.reachable(server_url)
                if problem:
                    raise _preflight_failed([problem])
            yield server_url, token or settings.SENTINEL_CONTROL_TOKEN
            return
        executor = MigrationExecutor(connection)
        if executor.migration_plan(executor.loader.graph.leaf_nodes()):
            call_command("migrate", interactive=False, verbosity=0)
        token = secrets.token_urlsafe(32)
        sealed = {
            "SENTINEL_CONTROL_TOKEN": token,
            "SENTINEL_FLAT_ENDPOINTS": "0",
            "SENTINEL_FAST_FORWARD_AWAKE": str(awake),
        }
        try:
            with site_server(
                log_path=Path(settings.VAR_DIR) / "bench-server.log", extra_env=sealed
            ) as url:
                self.stdout.write(f"Embedded server on {url}")
                yield url, token
        except ServerDidNotStart as exc:
            raise HarnessError(str(exc)) from None

    def progress(self, label: str = "") -> Progress:
        return Progress(self.stdout._out, label=label)

    # --- run -------------------------------------------------------------------------------

    def handle_run(
        self,
        *,
        name,
        config,
        parallel,
        task,
        filter,
        speed_factor,
        server_url,
        agent,
        model,
        model_url,
        clock,
        awake,
        retry_errors,
        results_dir,
        trials,
        noop_rule,
        jitter,
        seed,
        **_,
    ):
        if agent is None or Path(config).exists():
            # A built-in agent (--agent) stands in for the config's, which may then be absent.
            cfg = load_config(config, require_agent=agent is None)
        else:
            cfg = BenchConfig(None)
        if agent is None and cfg.agent_subprocess is None and cfg.reference_agent is None:
            raise _usage(f"{config}: agent_subprocess: is required (or pass --agent)")
        changes = reference_changes(cfg, agent, model, model_url)
        if changes:
            agent = None  # the reference agent replaces whatever the config named
        if speed_factor is not None:
            changes["speed_factor"] = validate_speed_factor(speed_factor)
        if parallel is not None:
            if parallel < 1:
                raise _usage(f"--parallel must be >= 1, got {parallel}")
            changes["parallel"] = parallel
        if server_url:
            changes["server_url"] = server_url.rstrip("/")
        if clock is not None:
            changes["clock"] = bench_clock(clock, "--clock")
        if awake is not None:
            if awake < 0:
                raise _usage(f"--awake must be >= 0 (0: no pacing), got {awake}")
            changes["awake"] = awake
        if trials < 1:
            raise _usage(f"--trials must be >= 1, got {trials}")
        if not 0 <= jitter <= MAX_CONDITION_AT:  # also rejects NaN
            raise _usage(
                f"--jitter must be between 0 and {MAX_CONDITION_AT:g} seconds, got {jitter}"
            )
        changes.update(noop_rule=noop_rule, jitter=jitter, seed=seed)
        cfg = dataclasses.replace(cfg, **changes)
        if cfg.awake and cfg.server_url:
            raise _usage(
                "awake paces the embedded server; a server of your own (server_url) paces by its "
                "own SENTINEL_FAST_FORWARD_AWAKE"
            )
        base_dir = Path(settings.BASE_DIR)
        # Before any server or task: a setup that cannot work runs nothing (preflight.py).
        problems = [] if agent else preflight.command_problems(cfg, base_dir)
        problems += preflight.model_problems(cfg.reference_agent)
        if problems:
            raise _preflight_failed(problems)
        run_dir = Path(results_dir) / name
        started_at = timezone.now()
        began = time.monotonic()
        with self.server(
            cfg.server_url, cfg.control_token, external_is_preflight=True, awake=cfg.awake
        ) as (
            url,
            token,
        ):
            client = ControlClient(url, token=token, timeout=cfg.http_timeout)
            try:
                invalid: list[dict] = []
                listing = discover(client, task=task, filter=filter, skipped=invalid)
                for entry in invalid:
                    self.stdout.write(f"Skipping {entry['path']} (invalid: {entry['error']})")
                problems = preflight.server_problems(listing, url)
                if problems:
                    raise _preflight_failed(problems)
                harness = Harness(
                    cfg,
                    client,
                    run_dir,
                    base_dir,
                    agent=agent,
                    retry_errors=retry_errors,
                    clock=cfg.clock,
                    private_paths=(Path(settings.SENTINEL_SCENARIO_DIR),),
                )
                tasks = harness.tasks(listing, trials)
                trials_note = f" ({len(listing)} scenarios × {trials} trials)" if trials > 1 else ""
                self.stdout.write(
                    f"Found {len(tasks)} tasks{trials_note}. Results -> {run_dir} "
                    f"(clock: {cfg.clock})"
                )
                if task:
                    self.stdout.write(f"Selecting tasks: {', '.join(task)}")
                if filter:
                    self.stdout.write(f"Filtering to tasks containing: {filter!r}")
                progress = self.progress()
                todo = harness.pending(tasks, progress)
                outcomes = run_pool([(harness, t) for t in todo], cfg.parallel, progress)
            finally:
                client.close()
        from apps.bench.records import record_benchmark

        reference = cfg.reference_agent
        label = agent or (f"{reference.kind} on {reference.model}" if reference else None)
        used = config_as_used(cfg, agent, trials)
        if cfg.jitter > 0:  # what the seed drew: each trial's shift of its timeline
            used["timeline_shifts"] = {t.label: t.shift for t in tasks}
        record_benchmark(name, run_dir, cfg, agent=label, started_at=started_at, raw_config=used)
        errors = task_errors(run_dir) if run_dir.is_dir() else []
        update_manifest(name, run_dir, used, tasks, started_at, base_dir, errors)
        write_set_summary(Path(results_dir), name, cfg, cfg.reaction_window)
        counts = {s: sum(o.status == s for o in outcomes) for s in ("passed", "failed", "error")}
        self.stdout.write(
            f"Done. ran={len(outcomes)} passed={counts['passed']} failed={counts['failed']} "
            f"errors={counts['error']} skipped={len(tasks) - len(todo)} wall_s={time.monotonic() - began:.1f}"
        )
        for line in error_lines(errors):
            self.stdout.write(line)
        if errors:
            raise CommandError(
                f"{len(errors)} task(s) are errors, not graded (causes above; their error.txt): "
                "fix the cause, then run again with --retry-errors",
                returncode=1,
            )

    # --- grade -----------------------------------------------------------------------------

    def handle_grade(
        self,
        *,
        names,
        csv,
        html,
        timely_window,
        task,
        filter,
        config,
        results_dir,
        judge,
        judge_url,
        judge_key_env,
        **_,
    ):
        from apps.bench import grading, report
        from apps.bench.judge import JudgeError, model_asker
        from apps.bench.ledger import not_written_line
        from apps.bench.timeline_links import timelines_section

        if config is None and Path(DEFAULT_CONFIG).exists():
            config = DEFAULT_CONFIG
        cfg = load_config(config, require_agent=False) if config else BenchConfig(None)
        window = cfg.reaction_window if timely_window is None else timely_window
        if not window > 0:  # also rejects NaN
            raise _usage(f"--timely-window must be a positive number of seconds, got {window}")
        sets = grading.load_result_sets(Path(results_dir), names, cfg, task=task, filter=filter)
        for result_set in sets:  # a results.json the harness did not write is no verdict
            for path in result_set.ignored:
                self.stderr.write(not_written_line(path))
        ask = (
            model_asker(judge, judge_url, os.environ.get(judge_key_env) or "none")
            if judge
            else None
        )
        try:
            for result_set in sets:
                grading.judge_reports(result_set.rows, ask, judge or "")
        except JudgeError as error:  # ours or the judge's, never the agent's: no figures
            raise CommandError(f"bench grade --judge: {error}") from None
        if not (task or filter):  # a summary.json is always of a whole set
            for result_set in sets:
                folder = Path(results_dir) / result_set.name
                try:
                    write_summary(folder, build_summary(result_set, window))
                except OSError as error:  # a set graded where it cannot be written: say so
                    self.stderr.write(f"{folder}/summary.json not written: {error.strerror}")
        if len(sets) == 1:  # one set: the upstream table, as before
            (one,) = sets
            text = (
                grading.render_csv(one.rows, one.errors)
                if csv
                else grading.render_table(one.rows, one.errors, window)
                + grading.provenance_line(one)
            )
        else:
            render = grading.render_comparison_csv if csv else grading.render_comparison
            text = render(sets, window)
        self.stdout.write(text, ending="")
        if not csv:
            self.stdout.write(timelines_section(sets, cfg.server_url), ending="")
        if html:
            if len(sets) == 1:
                report.write_report(
                    Path(html),
                    sets[0].name,
                    sets[0].rows,
                    window,
                    result_set=sets[0],
                    site=cfg.server_url,
                )
            else:
                report.write_comparison_report(Path(html), sets, window, site=cfg.server_url)
            if not csv:
                self.stdout.write(f"HTML report -> {html}")

    def handle_export_trajectories(self, *, results, out, results_dir, timely_window, **_):
        from apps.bench.trajectories import export_trajectories

        run_dir = Path(results)
        if not run_dir.is_dir() and (Path(results_dir) / results).is_dir():
            run_dir = Path(results_dir) / results
        if not run_dir.is_dir():
            raise _usage(f"RESULTS: no result set at {results} (nor under {results_dir}/)")
        if out:
            with open(out, "w", encoding="utf-8") as file:
                written, errors = export_trajectories(run_dir, file, timely_window)
        else:
            written, errors = export_trajectories(run_dir, self.stdout._out, timely_window)
        left_out = f", {errors} errors left out (no result)" if errors else ""
        self.stderr.write(f"{written} trajectories{left_out}" + (f" -> {out}" if out else ""))

    # --- validate --------------------------------------------------------------------------

    def unseen_triggers(self, listing: list[dict]) -> list[WatchCheck]:
        """Scenarios whose watched page does not change at condition_at, reported (not failed:
        the original's files run unchanged). Checked on this checkout's copy of each file, by
        its path; a scenario only the server has is not checked."""
        local = library(scenario_root()).by_path
        found = [local[s["path"]] for s in listing if s.get("path") in local]
        unseen = unseen_triggers(found)
        for check in unseen:
            self.stdout.write(f"unseen trigger: {check.scenario}: {check.detail}")
        return unseen

    def handle_validate(
        self,
        *,
        speed_factor,
        parallel,
        filter,
        server_url,
        reaction_window,
        keep,
        real_time,
        noop_rule,
        **_,
    ):
        sf = validate_speed_factor(speed_factor)
        if parallel < 1:
            raise _usage(f"--parallel must be >= 1, got {parallel}")
        if not reaction_window > 0:
            raise _usage(f"--reaction-window must be > 0, got {reaction_window}")
        cfg = BenchConfig(
            None,
            speed_factor=sf,
            parallel=parallel,
            reaction_window=reaction_window,
            noop_rule=noop_rule,
        )
        agents = CONTROL_AGENTS + CHEATING_AGENTS + WINDOW_AGENTS
        root = Path(tempfile.mkdtemp(prefix="bench-validate-"))
        began = time.monotonic()
        with self.server(server_url) as (url, token):
            client = ControlClient(url, token=token, timeout=cfg.http_timeout)
            try:
                invalid: list[dict] = []
                listing = discover(client, filter=filter, skipped=invalid)
                for entry in invalid:
                    self.stdout.write(f"Skipping {entry['path']} (invalid: {entry['error']})")
                problems = preflight.server_problems(listing, url)
                if problems:  # nothing validated is no proof of anything
                    raise _preflight_failed(problems)
                clock = "live" if real_time else "virtual"
                harnesses = {
                    a: Harness(
                        cfg,
                        client,
                        root / a,
                        Path(settings.BASE_DIR),
                        agent=a,
                        clock=clock,
                        private_paths=(Path(settings.SENTINEL_SCENARIO_DIR),),
                    )
                    for a in agents
                }
                tasks = {a: h.tasks(listing) for a, h in harnesses.items()}
                for a in WINDOW_AGENTS:  # an ephemeral condition's window is theirs to miss
                    tasks[a] = [t for t in tasks[a] if t.spec.get("condition_until") is not None]
                self.stdout.write(
                    f"Validating {len(listing)} scenarios with {', '.join(agents)} "
                    f"at speed factor {sf:g} on {clock} clocks (results -> {root})"
                )
                jobs = [(harnesses[a], t) for a in agents for t in tasks[a]]
                job_of = {t.folder: (h, t) for h, t in jobs}
                outcomes = run_pool(jobs, parallel * len(agents), self.progress())
                # An error (a control agent's own request timed out on a loaded machine, the
                # server hiccuped) says nothing about the scenario: run those tasks again.
                for _ in range(VALIDATE_RETRIES):
                    again = [o for o in outcomes if o.status == "error"]
                    if not again:
                        break
                    self.stdout.write(f"Running {len(again)} task(s) again after an error")
                    retry = [job_of[o.task.folder] for o in again]
                    for _, t in retry:
                        (t.folder / ERROR).unlink(missing_ok=True)
                    kept = [o for o in outcomes if o.status != "error"]
                    outcomes = kept + run_pool(retry, parallel * len(agents), self.progress())
            finally:
                client.close()
        wall = time.monotonic() - began
        errors = [o for o in outcomes if o.status == "error"]
        for o in errors:
            self.stdout.write(f"error (not a verdict): {o.label}{o.task.label}: {o.detail}")
        rows = {
            a: {r.name: r for r in load_rows(root / a)} if (root / a).is_dir() else {}
            for a in agents
        }
        ids = [s["id"] for s in listing]
        noop = {s["id"] for s in listing if s["noop"]}
        targeted = [i for i in ids if i not in noop]
        active = [t.scenario_id for t in tasks["oracle"] if t.category.startswith("active-")]

        def passed(agent: str, scenario: str) -> bool | None:
            row = rows[agent].get(scenario)
            return None if row is None else row.success

        problems = []
        oracle = [i for i in ids if passed("oracle", i)]
        problems += [f"oracle failed {i}" for i in ids if i not in oracle]
        early = [i for i in targeted if passed("early", i) is False]
        problems += [f"early passed {i} (trivially passable)" for i in targeted if i not in early]
        never = [i for i in ids if passed("never", i) is (i in noop)]
        problems += [
            f"never {'failed' if i in noop else 'passed'} {i}" for i in ids if i not in never
        ]
        sleeper = [i for i in ids if passed("sleeper", i)]
        ephemeral = [t.scenario_id for t in tasks["late"]]
        late = [i for i in ephemeral if passed("late", i)]
        problems += [f"late passed {i} (acting after the window closed)" for i in late]
        problems += cheating_problems(passed, ids, noop, active, noop_rule)
        unseen = self.unseen_triggers(listing)
        for problem in problems:
            self.stdout.write(f"PROBLEM: {problem}")
        if sleeper:
            self.stdout.write(
                f"sleeper (contacts just before the deadline) passes: {', '.join(sleeper)}"
            )
        figures = []
        for agent in CHEATING_AGENTS:
            summary = summarise(list(rows[agent].values()), reaction_window)
            success, timely = summary.rates["overall"], summary.timely["overall"]
            self.stdout.write(
                f"{agent} ({CHEATING_STRATEGIES[agent]}): success {success}, "
                f"timely success {timely} of the targeted tasks"
            )
            figures.append(
                f"{agent}={success.passed}/{success.total} "
                f"{agent}_timely={timely.passed}/{timely.total}"
            )
        if not keep:
            import shutil

            shutil.rmtree(root, ignore_errors=True)
        self.stdout.write(
            f"bench_validate: scenarios={len(ids)} oracle={len(oracle)}/{len(ids)} "
            f"early_fail={len(early)}/{len(targeted)} never_ok={len(never)}/{len(ids)} "
            f"sleeper={len(sleeper)}/{len(ids)} {' '.join(figures)} "
            f"late_ephemeral={len(late)}/{len(ephemeral)} "
            f"unseen={len(unseen)}/{len(targeted)} "
            f"wall_s={wall:.1f} clock={clock}"
        )
        if problems or errors:
            raise CommandError(
                f"validation failed: {len(problems)} problem(s), {len(errors)} harness error(s)",
                returncode=1,
            )


CHEATING_STRATEGIES = {
    "act_all": "acts on every item, contacts at the deadline",
    "fixed_time": "contacts at a fixed time",
    "quitter": "leaves at once",
}
