"""`bench grade`: read a results tree and summarise it; or compare several side by side.

First the upstream table, summary lines and CSV (upstream-protocol.md §6 "grade"), then the
paper's breakdown: success by category, reaction time of successful non-no-op tasks, USD cost
from costs.json × prices, tool-call statistics and server-measured agent activity.

Several result sets give the paper's comparison instead (one row per set), plus *timely
success*: a targeted task passed with a reaction time within a window, so an agent that contacts
just before the deadline on every passive task does not look as good as one that reacts at once.
It is a rate over the targeted tasks only: a no-op has no condition to be timely for, and doing
nothing must not score (its success is in the no-op column of the success table).

The reaction time is the server's (`reaction_time` in the verdict): from the condition to the
agent's first contact of either kind, a GET of the contact page or a POST of its form. Results
without it (the original harness's) are given the same rule here (`reaction_time_of`).

Times are those of results.json: simulated seconds ÷ the run's speed factor, i.e. wall seconds
on a live clock (and what they would have been, on `bench validate`'s virtual clocks).

Only a results.json the harness wrote is graded (ledger.py): any other is left out, each named
on one line (`ignored …`), and its task is neither a result nor hidden as one.
"""

from __future__ import annotations

import csv
import io
import json
import statistics
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from apps.bench.config import BenchConfig, input_tokens, output_tokens
from apps.bench.judge import Ask, Judgement, judge_result
from apps.bench.layout import COSTS, ERROR, RESULTS, BenchError, agent_files, error_cause_of
from apps.bench.ledger import Records
from apps.bench.manifest import read_manifest
from apps.bench.stats import (
    Interval,
    bootstrap_median,
    bootstrap_median_difference,
    newcombe_difference,
    pass_at_k,
    pass_hat_k,
    wilson,
)
from apps.scenarios.format import AXIS_DEFAULTS, TAXONOMY_CHOICES
from apps.scenarios.generated_names import family_of
from events.timing import REACTION_WINDOW

COLUMNS = (
    "name",
    "evaluation_time",
    "success",
    "stop_time",
    "condition_at",
    "reaction_time",
    "prompt_tokens",
    "completion_tokens",
    "tool_calls",
)
GROUPS = ("overall", "noop", "passive", "active", "absolute", "relative")
TIMELY_GROUPS = tuple(g for g in GROUPS if g != "noop")  # timely success: targeted tasks only


@dataclass
class Row:
    name: str
    environment: str
    category: str
    success: bool
    evaluation_time: float | None
    stop_time: float | None
    condition_at: float | None
    reaction_time: float | None
    prompt_tokens: int | None
    completion_tokens: int | None
    tool_calls: int | None
    cost_usd: float | None
    views: int | None
    actions: int | None
    run: int | None
    result: dict[str, Any] = field(default_factory=dict)
    costs: dict[str, Any] | None = None
    folder: Path | None = None  # the task's result folder (output; agent/: transcript, costs)
    trial: int = 1  # bench run --trials: which of the task's runs this is
    judgement: Judgement | None = None  # its report judged against the scenario's contact_rubric

    @property
    def label(self) -> str:
        return self.name if self.trial == 1 else f"{self.name} (trial {self.trial})"

    @property
    def is_noop(self) -> bool:
        return self.category == "noop"

    @property
    def persistence(self) -> str:
        """persistent | ephemeral (results from before the axis was recorded: persistent)."""
        return str(self.result.get("persistence") or AXIS_DEFAULTS["event_persistence"])

    @property
    def criteria(self) -> str:
        """objective | subjective (results from before the axis was recorded: objective)."""
        return str(self.result.get("criteria") or AXIS_DEFAULTS["criteria"])

    def in_group(self, group: str) -> bool:
        if group == "overall":
            return True
        if group == "noop":
            return self.is_noop
        return not self.is_noop and group in self.category.split("-")

    def timely(self, window: float) -> bool:
        """A targeted task passed with a contact within `window` s of the condition.

        Never a no-op, which has no condition to be timely for (timely rates leave no-ops out).
        A pass without a known reaction time is not timely, since lateness cannot be ruled out.
        """
        if not self.success or self.is_noop:
            return False
        return self.reaction_time is not None and self.reaction_time <= window

    @property
    def total_tokens(self) -> int | None:
        if self.prompt_tokens is None and self.completion_tokens is None:
            return None
        return (self.prompt_tokens or 0) + (self.completion_tokens or 0)

    @property
    def completion_time(self) -> float | None:
        """Wall seconds the run ran before the agent contacted or was stopped."""
        return self.stop_time if self.stop_time is not None else self.evaluation_time

    def per_minute(self, count: int | None) -> float | None:
        if count is None or not self.evaluation_time or self.evaluation_time < 1.0:
            return None  # a run shorter than a second says nothing about a rate
        return count / (self.evaluation_time / 60)


def _read_json(path: Path) -> Any:
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError):
        return None


def _parse_json(data: bytes) -> Any:
    try:
        return json.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError):
        return None


def _int(value: Any) -> int | None:
    return int(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else None


def first_contact(result: dict[str, Any]) -> float | None:
    """When the agent first made contact, of either kind (a GET or a POST-only contact)."""
    times = [result.get(k) for k in ("contact_get_time", "contact_post_time")]
    return min((t for t in times if t is not None), default=None)


def reaction_time_of(result: dict[str, Any]) -> float | None:
    """A pass's reaction time: the server's verdict's own, so `bench grade` and the verdict
    never differ; for a result without one (the original harness's), the same rule."""
    if not result.get("success"):
        return None
    if "reaction_time" in result:
        return result["reaction_time"]
    stop, condition = first_contact(result), result.get("condition_at")
    return None if stop is None or condition is None else stop - condition


def load_rows(
    run_dir: Path,
    config: BenchConfig | None = None,
    *,
    task: str | None = None,
    filter: str | None = None,
    ignored: list[Path] | None = None,
) -> list[Row]:
    """The graded tasks of a result set. A results.json the harness did not write (ledger.py)
    is left out, and appended to `ignored` when given, so the caller can say so."""
    if not run_dir.is_dir():
        raise BenchError(f"results folder not found: {run_dir}")
    records = Records.of(run_dir)
    rows = []
    for path, environment, name, trial in _result_files(run_dir, RESULTS):
        if (task is not None and name != task) or (filter and filter.lower() not in name.lower()):
            continue
        try:
            data = path.read_bytes()
        except OSError:
            continue
        if not records.vouches(path, data):
            if ignored is not None:
                ignored.append(path)
            continue
        result = _parse_json(data)
        if not isinstance(result, dict):
            continue
        costs = _read_json(agent_files(path.parent) / COSTS)
        costs = costs if isinstance(costs, dict) else None
        stop = first_contact(result)
        condition = result.get("condition_at")
        reaction = reaction_time_of(result)
        if reaction is not None and reaction < 0:
            raise BenchError(
                f"{path}: negative reaction time {reaction:.2f} s on a successful task"
            )
        category = result.get("category") or ("noop" if condition is None else "unknown")
        rows.append(
            Row(
                name=name,
                environment=environment,
                category=category,
                success=bool(result.get("success")),
                evaluation_time=result.get("evaluation_time"),
                stop_time=stop,
                condition_at=condition,
                reaction_time=reaction,
                prompt_tokens=_int(input_tokens(costs)) if costs else None,
                completion_tokens=_int(output_tokens(costs)) if costs else None,
                tool_calls=_int(costs.get("tool_calls")) if costs else None,
                cost_usd=config.cost_usd(costs) if config and costs else None,
                views=_int(result.get("views")),
                actions=_int(result.get("actions")),
                run=_int(result.get("run")),
                result=result,
                costs=costs,
                folder=path.parent,
                trial=trial,
            )
        )
    if not rows and (task or filter):
        raise BenchError(f"no results match {'--task ' + task if task else '--filter ' + filter!r}")
    return rows


def _result_files(run_dir: Path, filename: str) -> list[tuple[Path, str, str, int]]:
    """(path, environment, task name, trial) of every `filename` of a results tree, in order:
    trial 1 in `<env>/<task>/`, trial n in `<env>/<task>/trial-<n>/`."""
    found = [(p, p.parent.parent.name, p.parent.name, 1) for p in run_dir.glob(f"*/*/{filename}")]
    for path in run_dir.glob(f"*/*/trial-*/{filename}"):
        number = path.parent.name.removeprefix("trial-")
        if number.isdigit() and int(number) > 1:
            found.append(
                (path, path.parent.parent.parent.name, path.parent.parent.name, int(number))
            )
    return sorted(found, key=lambda entry: (entry[1], entry[2], entry[3]))


@dataclass(frozen=True)
class TaskError:
    """A task whose outcome is `error` (error.txt, no results.json): not graded, not counted."""

    name: str
    environment: str
    trial: int
    cause: str

    def __str__(self) -> str:
        return self.name if self.trial == 1 else f"{self.name} (trial {self.trial})"


def task_errors(run_dir: Path) -> list[TaskError]:
    """Errored tasks: error.txt and no results.json of the harness's (one it did not write
    hides no error)."""
    records = Records.of(run_dir)
    return [
        TaskError(name, environment, trial, error_cause_of(path.parent))
        for path, environment, name, trial in _result_files(run_dir, ERROR)
        if not records.vouches(path.parent / RESULTS)
    ]


# --- statistics ------------------------------------------------------------------------------


def _values(rows: list[Row], attribute: str) -> list[float]:
    return [v for v in (getattr(r, attribute) for r in rows) if v is not None]


def mean(values: list[float]) -> float | None:
    return statistics.fmean(values) if values else None


def median(values: list[float]) -> float | None:
    return statistics.median(values) if values else None


def quartiles(values: list[float]) -> tuple[float, float] | None:
    if len(values) < 2:
        return (values[0], values[0]) if values else None
    q = statistics.quantiles(values, n=4, method="inclusive")
    return q[0], q[2]


@dataclass(frozen=True)
class Rate:
    passed: int
    total: int

    @property
    def fraction(self) -> float | None:
        return self.passed / self.total if self.total else None

    def __str__(self) -> str:
        return (
            f"{100 * self.fraction:.1f}% ({self.passed}/{self.total})"
            if self.total
            else "N/A (0/0)"
        )


def rates_by_group(rows: list[Row], passed: Callable[[Row], bool]) -> dict[str, Rate]:
    rates = {}
    for group in GROUPS:
        members = [r for r in rows if r.in_group(group)]
        rates[group] = Rate(sum(passed(r) for r in members), len(members))
    return rates


def success_by_group(rows: list[Row]) -> dict[str, Rate]:
    return rates_by_group(rows, lambda r: r.success)


def timely_by_group(rows: list[Row], window: float) -> dict[str, Rate]:
    """Timely success per group, over the targeted tasks (the no-op group is empty)."""
    return rates_by_group([r for r in rows if not r.is_noop], lambda r: r.timely(window))


@dataclass(frozen=True)
class Summary:
    total: int
    successes: int
    rates: dict[str, Rate]
    reaction: list[float]
    prompt_tokens: list[float]
    completion_tokens: list[float]
    tool_calls: list[float]
    costs: list[float]
    views_per_min: list[float]
    actions_per_min: list[float]
    timely: dict[str, Rate]
    unpriced: int  # tasks without a USD cost: no costs.json, or its model has no price
    total_tokens: list[float]


def summarise(rows: list[Row], window: float = REACTION_WINDOW) -> Summary:
    successful = [r for r in rows if r.success]
    return Summary(
        total=len(rows),
        successes=len(successful),
        rates=success_by_group(rows),
        timely=timely_by_group(rows, window),
        unpriced=sum(r.cost_usd is None for r in rows),
        total_tokens=_values(rows, "total_tokens"),
        # Reaction time: successful non-no-op tasks (a no-op has no condition to react to).
        reaction=_values([r for r in successful if not r.is_noop], "reaction_time"),
        prompt_tokens=_values(rows, "prompt_tokens"),
        completion_tokens=_values(rows, "completion_tokens"),
        tool_calls=_values(rows, "tool_calls"),
        costs=_values(rows, "cost_usd"),
        views_per_min=[v for v in (r.per_minute(r.views) for r in rows) if v is not None],
        actions_per_min=[v for v in (r.per_minute(r.actions) for r in rows) if v is not None],
    )


# --- rendering -------------------------------------------------------------------------------


def _cell(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return f"{value:.2f}"
    return str(value)


def row_values(row: Row) -> list[Any]:
    return [
        row.label,
        row.evaluation_time,
        row.success,
        row.stop_time,
        row.condition_at,
        row.reaction_time,
        row.prompt_tokens,
        row.completion_tokens,
        row.tool_calls,
    ]


def _avg_median(values: list[float], unit: str = "", digits: int = 1) -> str:
    if not values:
        return "N/A"
    return f"avg {mean(values):.{digits}f}{unit}, median {median(values):.{digits}f}{unit}"


def aligned(header: list[str], lines: list[list[str]]) -> list[str]:
    """A plain-text table: columns padded to their widest cell, a rule under the header."""
    widths = [max(len(line[i]) for line in [header, *lines]) for i in range(len(header))]

    def joined(line: list[str]) -> str:
        return " | ".join(c.ljust(w) for c, w in zip(line, widths, strict=True)).rstrip()

    return [joined(header), "-+-".join("-" * w for w in widths), *(joined(x) for x in lines)]


def clocks(rows: list[Row]) -> str:
    """The clocks the tasks ran on ("live", or e.g. "fast_forward 18, live 2"); results written
    before fast-forward existed ran live."""
    counts: dict[str, int] = {}
    for row in rows:
        clock = str(row.result.get("clock") or "live")
        counts[clock] = counts.get(clock, 0) + 1
    if len(counts) <= 1:
        return next(iter(counts), "live")
    return ", ".join(f"{clock} {n}" for clock, n in sorted(counts.items()))


def render_table(
    rows: list[Row], errors: list[TaskError] | None = None, window: float = REACTION_WINDOW
) -> str:
    out = aligned(list(COLUMNS), [[_cell(v) for v in row_values(r)] for r in rows])
    s = summarise(rows, window)
    out += [
        "",
        f"Total Tasks: {s.total}",
        f"Clock: {clocks(rows)}",
        f"Task Success Rate: {s.rates['overall']}",
        f"Reaction Time: {_avg_median(s.reaction, 's')}",
        f"Prompt Tokens: {_avg_median(s.prompt_tokens)}",
        f"Completion Tokens: {_avg_median(s.completion_tokens)}",
        f"Tool Calls: {_avg_median(s.tool_calls)}",
        "",
        "Success by category: " + " | ".join(f"{g} {s.rates[g]}" for g in GROUPS),
        "Reaction Time (successful, non-no-op): "
        + (
            f"mean {mean(s.reaction):.1f}s, median {median(s.reaction):.1f}s (n={len(s.reaction)})"
            if s.reaction
            else "N/A"
        ),
        "Cost (USD): "
        + (
            f"median ${median(s.costs):.4f}, mean ${mean(s.costs):.4f} (n={len(s.costs)})"
            if s.costs
            else "N/A"
        ),
        "Tool Calls: " + _tool_stats(s.tool_calls),
        "Agent activity (server-measured, per minute of run): "
        + (
            f"views {mean(s.views_per_min):.1f}/min, actions {mean(s.actions_per_min):.1f}/min"
            if s.views_per_min
            else "N/A"
        ),
    ]
    out += report_lines(rows)
    out += uncertainty_lines(rows, window)
    out += error_lines(errors or [])
    return "\n".join(out) + "\n"


def judge_reports(rows: list[Row], ask: Ask | None, model: str) -> None:
    """Judge every report that has a rubric (by `ask`'s model, else by its keywords)."""
    for row in rows:
        row.judgement = judge_result(row.result, row.folder, ask, model)


@dataclass(frozen=True)
class ReportCorrectness:
    judged: Rate  # reports judged correct, of those judged
    success_with_report: Rate  # passed with a correct report, of the tasks with a rubric
    by: str  # who judged ("keywords", a model's name, or several)


def report_correctness(rows: list[Row]) -> ReportCorrectness | None:
    """None when no task of `rows` has a judged report."""
    judged = [r for r in rows if r.judgement is not None]
    if not judged:
        return None
    with_rubric = [r for r in rows if r.result.get("contact_rubric")]
    correct = sum(r.judgement.correct for r in judged if r.judgement is not None)
    both = sum(r.success and r.judgement is not None and r.judgement.correct for r in with_rubric)
    judges = sorted({r.judgement.by for r in judged if r.judgement is not None})
    return ReportCorrectness(
        Rate(correct, len(judged)), Rate(both, len(with_rubric)), ", ".join(judges)
    )


def report_lines(rows: list[Row]) -> list[str]:
    found = report_correctness(rows)
    if found is None:
        return []
    return [
        f"Reports judged correct ({found.by}): {found.judged}",
        f"Success with a correct report (tasks with a contact rubric): {found.success_with_report}",
    ]


def _tool_stats(values: list[float]) -> str:
    if not values:
        return "N/A"
    q1, q3 = quartiles(values)
    return (
        f"mean {mean(values):.1f}, median {median(values):.1f}, q1 {q1:.1f}, q3 {q3:.1f}, "
        f"min {min(values):g}, max {max(values):g}"
    )


def _fmt1(value: float | None) -> str:
    return "" if value is None else f"{value:.1f}"


def render_csv(rows: list[Row], errors: list[TaskError] | None = None) -> str:
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(COLUMNS)
    for row in rows:
        writer.writerow(["" if v is None else v for v in row_values(row)])
    writer.writerow([])
    s = summarise(rows)
    rate = s.rates["overall"].fraction
    pairs = [
        ("Total Tasks", s.total),
        ("Successes", s.successes),
        ("Task Success Rate", "" if rate is None else f"{rate:.4f}"),
        ("Average Reaction Time", _fmt1(mean(s.reaction))),
        ("Median Reaction Time", _fmt1(median(s.reaction))),
        ("Average Prompt Tokens", _fmt1(mean(s.prompt_tokens))),
        ("Median Prompt Tokens", _fmt1(median(s.prompt_tokens))),
        ("Average Completion Tokens", _fmt1(mean(s.completion_tokens))),
        ("Median Completion Tokens", _fmt1(median(s.completion_tokens))),
        ("Average Tool Calls", _fmt1(mean(s.tool_calls))),
        ("Median Tool Calls", _fmt1(median(s.tool_calls))),
    ]
    # Ours, after the upstream rows so upstream readers still find theirs first.
    for group in GROUPS[1:]:
        fraction = s.rates[group].fraction
        pairs.append((f"Success Rate {group}", "" if fraction is None else f"{fraction:.4f}"))
    pairs += [
        ("Median Cost USD", "" if not s.costs else f"{median(s.costs):.4f}"),
        ("Average Cost USD", "" if not s.costs else f"{mean(s.costs):.4f}"),
        ("Average Views Per Minute", _fmt1(mean(s.views_per_min))),
        ("Average Actions Per Minute", _fmt1(mean(s.actions_per_min))),
    ]
    pairs.append(("Errors Not Graded", len(errors or [])))
    writer.writerows(pairs)
    return buffer.getvalue()


# --- several result sets, side by side ------------------------------------------------------


@dataclass(frozen=True)
class ResultSet:
    """One named results tree (`<results-dir>/<name>/`), read for grading."""

    name: str
    rows: list[Row]
    errors: list[TaskError]
    manifest: dict[str, Any] | None = None
    ignored: list[Path] = field(default_factory=list)  # results.json the harness did not write


def load_result_sets(
    results_dir: Path,
    names: list[str],
    config: BenchConfig | None = None,
    *,
    task: str | None = None,
    filter: str | None = None,
) -> list[ResultSet]:
    """Every named set, in the order given; a missing name fails before any output."""
    repeated = sorted({n for n in names if names.count(n) > 1})
    if repeated:
        raise BenchError(f"result set named twice: {repeated[0]}")
    missing = [n for n in names if not (results_dir / n).is_dir()]
    if missing:
        present = (
            sorted(p.name for p in results_dir.iterdir() if p.is_dir())
            if results_dir.is_dir()
            else []
        )
        raise BenchError(
            f"results folder not found: {results_dir / missing[0]} "
            f"(result sets in {results_dir}: {', '.join(present) or 'none'})"
        )
    sets = []
    for name in names:
        ignored: list[Path] = []
        rows = load_rows(results_dir / name, config, task=task, filter=filter, ignored=ignored)
        errors = [] if task or filter else task_errors(results_dir / name)
        sets.append(ResultSet(name, rows, errors, read_manifest(results_dir / name), ignored))
    return sets


CATEGORY_HEADERS = {"noop": "no-op"}


def _rate_cells(rates: dict[str, Rate], groups: tuple[str, ...] = GROUPS) -> list[str]:
    return [str(rates[g]) for g in groups[1:]]


def stat_cells(values: list[float], fmt: Callable[[float], str]) -> list[str]:
    """n, mean, median, q1, q3, min, max — the paper's tool-call table, for any values."""
    if not values:
        return ["0"] + ["N/A"] * 6
    q1, q3 = quartiles(values)
    return [str(len(values))] + [
        fmt(v) for v in (mean(values), median(values), q1, q3, min(values), max(values))
    ]


STAT_HEADERS = ["n", "mean", "median", "q1", "q3", "min", "max"]


def unpriced_models(sets: list[ResultSet]) -> list[str]:
    """Models named in a costs.json that the config has no price for."""
    return sorted(
        {
            str(r.costs["model"])
            for rs in sets
            for r in rs.rows
            if r.costs and r.cost_usd is None and r.costs.get("model")
        }
    )


# The comparison's tables, one row per result set: (header, rows), drawn as text by
# render_comparison and as HTML by report.render_comparison_report.
TableCells = tuple[list[str], list[list[str]]]
Summaries = list[tuple[ResultSet, Summary]]


def _category_headers(groups: tuple[str, ...] = GROUPS) -> list[str]:
    return [CATEGORY_HEADERS.get(g, g) for g in groups[1:]]


def success_table(summaries: Summaries) -> TableCells:
    header = ["result set", "tasks", "success", "timely", *_category_headers()]
    return header, [
        [
            rs.name,
            str(s.total),
            str(s.rates["overall"]),
            str(s.timely["overall"]),
            *_rate_cells(s.rates),
        ]
        for rs, s in summaries
    ]


# The paper's future-work axes as (Row attribute, its values): one column per value.
AXIS_COLUMNS = tuple(
    (attribute, value)
    for attribute, key in (("persistence", "event_persistence"), ("criteria", "criteria"))
    for value in TAXONOMY_CHOICES[key]
)


def axis_rate(rows: list[Row], attribute: str, value: str, window: float, timely: bool) -> Rate:
    """Success (or timely success, of the targeted tasks) among the tasks whose `attribute`
    (persistence or criteria) is `value`."""
    members = [r for r in rows if getattr(r, attribute) == value and not (timely and r.is_noop)]
    return Rate(sum(r.timely(window) if timely else r.success for r in members), len(members))


def axis_table(sets: list[ResultSet], window: float, *, timely: bool = False) -> TableCells:
    """One row per result set: success (or timely success, of the targeted tasks) among the
    persistent and the ephemeral tasks, the objective and the subjective ones."""
    return ["result set", *(value for _, value in AXIS_COLUMNS)], [
        [rs.name, *(str(axis_rate(rs.rows, a, v, window, timely)) for a, v in AXIS_COLUMNS)]
        for rs in sets
    ]


def timely_table(summaries: Summaries) -> TableCells:
    header = ["result set", "timely", *_category_headers(TIMELY_GROUPS)]
    return header, [
        [rs.name, str(s.timely["overall"]), *_rate_cells(s.timely, TIMELY_GROUPS)]
        for rs, s in summaries
    ]


def cost_table(summaries: Summaries) -> TableCells:
    return ["result set", *STAT_HEADERS, "unpriced"], [
        [rs.name, *stat_cells(s.costs, lambda v: f"${v:.4f}"), str(s.unpriced)]
        for rs, s in summaries
    ]


def tool_calls_table(summaries: Summaries) -> TableCells:
    return ["result set", *STAT_HEADERS], [
        [rs.name, *stat_cells(s.tool_calls, lambda v: f"{v:.1f}")] for rs, s in summaries
    ]


def render_comparison(sets: list[ResultSet], window: float) -> str:
    """The console comparison: one row per result set in every table."""
    summaries = [(rs, summarise(rs.rows, window)) for rs in sets]
    named = ", ".join(f"{rs.name} (clock: {clocks(rs.rows)})" for rs in sets)
    out = [f"Comparing {len(sets)} result sets: {named}", ""]
    out.append(
        f"Success by category (timely = targeted tasks passed with reaction time <= {window:g} s;"
        " no-ops apart)"
    )
    out += aligned(*success_table(summaries))
    out += ["", f"Timely success by category (targeted tasks, reaction time <= {window:g} s)"]
    out += aligned(*timely_table(summaries))
    out += ["", "Success by persistence and criteria"]
    out += aligned(*axis_table(sets, window))
    out += ["", f"Timely success by persistence and criteria (targeted tasks, <= {window:g} s)"]
    out += aligned(*axis_table(sets, window, timely=True))
    judged = [f"{rs.name}: {line}" for rs in sets for line in report_lines(rs.rows)]
    out += ["", *judged] if judged else []
    out += ["", "Cost per task (USD; costs.json tokens x config prices)"]
    out += aligned(*cost_table(summaries))
    out += ["", "Tokens per task (input + output, costs.json)"]
    out += aligned(
        ["result set", *STAT_HEADERS],
        [[rs.name, *stat_cells(s.total_tokens, lambda v: f"{v:.0f}")] for rs, s in summaries],
    )
    out += ["", "Tool calls per task (costs.json)"]
    out += aligned(*tool_calls_table(summaries))
    out += [
        "",
        "Reaction time (passed targeted tasks; seconds = simulated seconds / speed factor)",
    ]
    out += aligned(
        ["result set", "n", "mean", "median"],
        [
            [
                rs.name,
                str(len(s.reaction)),
                _seconds(mean(s.reaction)),
                _seconds(median(s.reaction)),
            ]
            for rs, s in summaries
        ],
    )
    if unpriced_models(sets):
        out += ["", f"No price in the config for model(s): {', '.join(unpriced_models(sets))}"]
    out += ["", "Differences beyond the noise (95 % intervals; first set minus each other)"]
    out += aligned(*difference_table(sets, window))
    for rs in sets:
        out += error_lines(rs.errors, prefix=f"{rs.name}: ")
    return "\n".join(out) + "\n"


def _seconds(value: float | None) -> str:
    return "N/A" if value is None else f"{value:.1f}s"


def render_comparison_csv(sets: list[ResultSet], window: float) -> str:
    """One CSV row per result set; rates are fractions, empty where undefined."""

    def fraction(rate: Rate) -> str:
        return "" if rate.fraction is None else f"{rate.fraction:.4f}"

    def stats(values: list[float]) -> list[str]:
        if not values:
            return ["0"] + [""] * 6
        q1, q3 = quartiles(values)
        return [str(len(values))] + [
            f"{v:.4f}" for v in (mean(values), median(values), q1, q3, min(values), max(values))
        ]

    header = ["result_set", "tasks", "success_rate", "timely_success_rate"]
    header += [f"success_{g}" for g in GROUPS[1:]] + [f"timely_{g}" for g in TIMELY_GROUPS[1:]]
    header += [f"{kind}_{value}" for kind in ("success", "timely") for _, value in AXIS_COLUMNS]
    for prefix in ("cost_usd", "tool_calls", "tokens"):
        header += [f"{prefix}_{h}" for h in STAT_HEADERS]
    header += ["unpriced_tasks", "reaction_n", "reaction_mean_s", "reaction_median_s"]
    header += ["timely_window_s", "error_tasks"]
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(header)
    for rs in sets:
        s = summarise(rs.rows, window)
        writer.writerow(
            [rs.name, s.total, fraction(s.rates["overall"]), fraction(s.timely["overall"])]
            + [fraction(s.rates[g]) for g in GROUPS[1:]]
            + [fraction(s.timely[g]) for g in TIMELY_GROUPS[1:]]
            + [
                fraction(axis_rate(rs.rows, attribute, value, window, timely))
                for timely in (False, True)
                for attribute, value in AXIS_COLUMNS
            ]
            + stats(s.costs)
            + stats(s.tool_calls)
            + stats(s.total_tokens)
            + [s.unpriced, len(s.reaction), _fmt1(mean(s.reaction)), _fmt1(median(s.reaction))]
            + [f"{window:g}", len(rs.errors)]
        )
    return buffer.getvalue()


# --- uncertainty: intervals, trials, breakdowns (stats.py) -----------------------------------


def percent_interval(interval: Interval | None) -> str:
    return "N/A" if interval is None else f"{100 * interval.low:.1f}–{100 * interval.high:.1f}%"


def rate_with_interval(rate: Rate) -> str:
    """`66.7% (4/6) [30.0–90.3%]`: the rate, its counts and its Wilson 95 % interval."""
    if not rate.total:
        return str(rate)
    return f"{rate} [{percent_interval(wilson(rate.passed, rate.total))}]"


def median_with_interval(values: list[float], fmt: Callable[[float], str]) -> str:
    if not values:
        return "N/A"
    interval = bootstrap_median(values)
    bounds = "" if interval is None else f" [{fmt(interval.low)}–{fmt(interval.high)}]"
    return f"{fmt(median(values))}{bounds} (n={len(values)})"


def _usd(value: float) -> str:
    return f"${value:.4f}"


def _secs(value: float) -> str:
    return f"{value:.1f}s"


def interval_table(rows: list[Row], window: float) -> TableCells:
    """The headline figures with their 95 % intervals (Wilson for rates, bootstrap medians)."""
    s = summarise(rows, window)
    return ["figure", "value [95% interval]"], [
        ["success", rate_with_interval(s.rates["overall"])],
        [f"timely success (<= {window:g} s)", rate_with_interval(s.timely["overall"])],
        ["median reaction time", median_with_interval(s.reaction, _secs)],
        ["median cost per task", median_with_interval(s.costs, _usd)],
        ["median tokens per task", median_with_interval(s.total_tokens, lambda v: f"{v:.0f}")],
    ]


def _by_task(rows: list[Row]) -> dict[tuple[str, str], list[Row]]:
    tasks: dict[tuple[str, str], list[Row]] = {}
    for row in rows:
        tasks.setdefault((row.environment, row.name), []).append(row)
    return tasks


def trials_of(rows: list[Row]) -> int:
    """The number of trials the set was run with: the most any task has (1 without --trials)."""
    return max((len(trials) for trials in _by_task(rows).values()), default=0)


@dataclass(frozen=True)
class PassK:
    k: int
    tasks: int  # tasks with at least k graded trials (the others are left out)
    left_out: int
    at_k: float | None  # pass@k, averaged over tasks
    all_k: float | None  # pass^k, averaged over tasks


def pass_k(rows: list[Row], k: int | None = None) -> PassK:
    """pass@k and pass^k over the tasks that have k graded trials (errors are not trials)."""
    tasks = _by_task(rows)
    k = k or trials_of(rows)
    full = [trials for trials in tasks.values() if len(trials) >= k]
    if not full or k < 1:
        return PassK(k, 0, len(tasks), None, None)
    counts = [(len(trials), sum(r.success for r in trials)) for trials in full]
    return PassK(
        k,
        len(full),
        len(tasks) - len(full),
        statistics.fmean(pass_at_k(n, c, k) for n, c in counts),
        statistics.fmean(pass_hat_k(n, c, k) for n, c in counts),
    )


def pass_k_line(rows: list[Row]) -> str | None:
    result = pass_k(rows)
    if result.k < 2 or result.at_k is None or result.all_k is None:
        return None
    left = (
        f"; {result.left_out} task(s) with fewer graded trials left out" if result.left_out else ""
    )
    return (
        f"pass@{result.k} {100 * result.at_k:.1f}%, pass^{result.k} {100 * result.all_k:.1f}% "
        f"over {result.tasks} tasks × {result.k} trials{left}"
    )


def breakdown_table(
    rows: list[Row], window: float, key: Callable[[Row], str], title: str
) -> TableCells:
    """One line per group (environment or category): attempts, success and timely success with
    their intervals, the median reaction time with its interval."""
    groups: dict[str, list[Row]] = {}
    for row in rows:
        groups.setdefault(key(row), []).append(row)
    lines = []
    for name in sorted(groups):
        members = groups[name]
        s = summarise(members, window)
        lines.append(
            [
                name,
                str(len(members)),
                rate_with_interval(s.rates["overall"]),
                rate_with_interval(s.timely["overall"]),
                median_with_interval(s.reaction, _secs),
            ]
        )
    return [title, "attempts", "success [95%]", "timely [95%]", "median reaction [95%]"], lines


def environment_table(rows: list[Row], window: float) -> TableCells:
    return breakdown_table(rows, window, lambda r: r.environment, "environment")


def category_table(rows: list[Row], window: float) -> TableCells:
    """The paper's categories, then the tasks by persistence and by criteria (the axes its
    future work names: an ephemeral condition holds only briefly, a subjective one is a
    judgement against a rubric)."""
    header, lines = breakdown_table(rows, window, lambda r: r.category, "category")
    for axis in ("persistence", "criteria"):
        lines += breakdown_table(rows, window, lambda r, a=axis: f"{a}: {getattr(r, a)}", axis)[1]
    return header, lines


def family_table(rows: list[Row], window: float) -> TableCells:
    """Generated scenarios (`manage.py generate`) by their family; others under their id."""
    return breakdown_table(
        rows, window, lambda r: f"{r.environment}/{family_of(r.name) or r.name}", "family"
    )


def uncertainty_lines(rows: list[Row], window: float = REACTION_WINDOW) -> list[str]:
    """The figures with their 95 % intervals, pass@k/pass^k, by environment and by category."""
    if not rows:
        return []
    out = ["", "With 95 % intervals (Wilson for rates, bootstrap for medians):"]
    out += aligned(*interval_table(rows, window))
    line = pass_k_line(rows)
    if line:
        out += ["", line]
    out += ["", "By environment:", *aligned(*environment_table(rows, window))]
    out += ["", "By category:", *aligned(*category_table(rows, window))]
    if any(family_of(r.name) for r in rows):
        out += ["", "By family (generated scenarios):", *aligned(*family_table(rows, window))]
    return out


def error_lines(errors: list[TaskError], prefix: str = "") -> list[str]:
    """Errors are counted apart and listed with their cause (never graded, never in a rate)."""
    if not errors:
        return []
    out = ["", f"{prefix}errors (not graded, not in any rate): {len(errors)}"]
    out += [f"  {e.environment}/{e}: {e.cause or 'no cause recorded'}" for e in errors]
    return out


def outcome_counts(rows: list[Row], errors: list[TaskError]) -> dict[str, int]:
    passed = sum(r.success for r in rows)
    return {"passed": passed, "failed": len(rows) - passed, "error": len(errors)}


def _difference_cells(
    name: str, first: str, other: str, diff: str, interval: Interval | None, unit: str
) -> list[str]:
    if interval is None:
        return [name, first, other, diff, "N/A", "too few to say"]
    bounds = f"{interval.low:+.1f} to {interval.high:+.1f}{unit}"
    verdict = "within the noise" if interval.contains(0.0) else "beyond the noise"
    return [name, first, other, diff, bounds, verdict]


def difference_table(sets: list[ResultSet], window: float) -> TableCells:
    """Each set against the first: a difference counts only when its 95 % interval leaves out 0
    (Newcombe's interval for rates; a bootstrap interval for the median reaction time)."""
    header = ["figure", "first", "other", "difference", "95% interval", "verdict"]
    lines = []
    base, *others = sets
    sb = summarise(base.rows, window)
    for rs in others:
        so = summarise(rs.rows, window)
        for label, rb, ro in (
            ("success", sb.rates["overall"], so.rates["overall"]),
            ("timely success", sb.timely["overall"], so.timely["overall"]),
        ):
            result = newcombe_difference(rb.passed, rb.total, ro.passed, ro.total)
            diff, interval = result if result else (None, None)
            lines.append(
                _difference_cells(
                    f"{label}: {base.name} − {rs.name}",
                    str(rb),
                    str(ro),
                    "N/A" if diff is None else f"{100 * diff:+.1f} pts",
                    None if interval is None else Interval(100 * interval.low, 100 * interval.high),
                    " pts",
                )
            )
        interval = bootstrap_median_difference(sb.reaction, so.reaction)
        mb, mo = median(sb.reaction), median(so.reaction)
        lines.append(
            _difference_cells(
                f"median reaction: {base.name} − {rs.name}",
                _seconds(mb),
                _seconds(mo),
                "N/A" if mb is None or mo is None else f"{mb - mo:+.1f}s",
                interval,
                "s",
            )
        )
    return header, lines


def provenance_line(rs: ResultSet) -> str:
    """One line from the set's manifest.json: what produced it (the HTML report shows it all)."""
    m = rs.manifest
    if m is None:
        return f"\nProduced by: unknown (no {rs.name}/manifest.json)\n"
    config = m.get("config") or {}
    return (
        f"\nProduced by: version {m.get('version')}, commit {m.get('commit')}, "
        f"speed factor {config.get('speed_factor')}, trials {config.get('trials', 1)}, "
        f"{m.get('started_at')} – {m.get('finished_at')} on {(m.get('machine') or {}).get('host')} "
        f"(manifest.json)\n"
    )
